// The radiance a strand fragment reflects towards the eye, by its prim's
// hair material: flat displayColor (look-dev, and tests whose pixels can be
// computed by hand), Kajiya-Kay, or Marschner with its azimuthal terms from
// tables or evaluated per fragment; lit by every light of the pass plus
// (first pass only) the dome's ambient or uniform term. SRBF lights of a
// dome read their material's convolution table (srbfLighting.glsl). Each
// light's irradiance is scaled by its shadow transmittance at the strand's
// centre line `centre`, or as strand.tese looked it up there with vertex
// shadows (the same for Kajiya-Kay and Marschner; the ambient and uniform
// dome terms are not shadowed). `segment` and `u` locate the fragment on its
// span, for parameters that vary along the prim.
// Needs frameUniforms.glsl, lights.glsl, kajiyaKay.glsl, marschner.glsl,
// marschnerAnalytic.glsl, catmullRom.glsl, hairMaterials.glsl,
// shadowFragmentLists.glsl, shadows.glsl and srbfLighting.glsl, after
// shadingFeatures.glsl, whose switches cut out what the frame does not use.
#ifdef HDHAIR_VERTEX_SHADOWS
// The pass's first HDHAIR_VERTEX_SHADOWS lights as strand.tese looked them
// up at the segment's ends, 4 a vec4, interpolated along it
// (shadowSampling=vertex); the lights after them have no map. Selected, not
// indexed, and no per-fragment lookup compiled at all: llvmpipe would run it
// masked anyway.
layout(location = 6) in vec4 vertexTransmittance[HDHAIR_VERTEX_SHADOW_VECTORS];
float strandShadowTransmittance(int i, vec3 centre) {
#if HDHAIR_VERTEX_SHADOW_VECTORS == 1
    vec4 four = vertexTransmittance[0];
#else
    vec4 four = vertexTransmittance[clamp(i / 4, 0, HDHAIR_VERTEX_SHADOW_VECTORS - 1)];
#endif
    return i < HDHAIR_VERTEX_SHADOWS ? dot(four, vec4(equal(ivec4(i % 4), ivec4(0, 1, 2, 3)))) : 1.0;
}
float strandSrbfShadowTransmittance(int i, vec3 centre) { return strandShadowTransmittance(i, centre); }
#else
float strandShadowTransmittance(int i, vec3 centre) { return shadowTransmittance(i, centre); }
float strandSrbfShadowTransmittance(int i, vec3 centre) { return srbfShadowTransmittance(i, centre); }
#endif

vec3 strandRadiance(vec3 worldPosition, vec3 centre, vec3 worldTangent, vec3 hairColor, int materialIndex, int segment,
                    float u) {
    HairShading shading = hairShadingAt(materialIndex, segment, u);
    // Flat colour is unlit: it belongs to the first light batch alone, so
    // that summing batches counts it once.
    if (shading.model == 0) return lights.lightCount.y == 0 ? hairColor : vec3(0.0);
#if HDHAIR_FEATURE_KAJIYA_KAY || HDHAIR_FEATURE_MARSCHNER_TABLED || HDHAIR_FEATURE_MARSCHNER_ANALYTIC
    vec3 t = normalize(worldTangent);
    vec3 e = directionToEye(worldPosition);
#if HDHAIR_FEATURE_SRBF_ABSORPTION
    SrbfAbsorption absorption = srbfAbsorption(shading, t, e);
#else
    SrbfAbsorption absorption = srbfNoAbsorption();
#endif
#if HDHAIR_FEATURE_UNIFORM_DOME
    vec3 radiance =
        lights.ambient.w > 0.5
            ? lights.ambient.rgb * srbfUniformDomeResponse(materialIndex, shading, absorption, t, e, hairColor)
            : lights.ambient.rgb * hairColor;
#else
    vec3 radiance = lights.ambient.rgb * hairColor;
#endif
    bool analytic = (shading.flags & HAIR_MATERIAL_ANALYTIC) != 0;
    for (int i = 0; i < lights.lightCount.x; ++i) {
#if HDHAIR_FEATURE_SRBF_LIGHTS
        if (isSrbfLight(i)) {
            vec3 lobe = srbfLightRadiance(i, materialIndex, shading, absorption, t, e, hairColor);
            if (any(greaterThan(lobe, vec3(0.0)))) radiance += lobe * strandSrbfShadowTransmittance(i, centre);
            continue;
        }
#endif
        vec3 l;
        vec3 irradiance = lightIrradiance(i, worldPosition, l);
        if (all(equal(irradiance, vec3(0.0)))) continue;  // unlit here: no shadow lookup
        irradiance *= strandShadowTransmittance(i, centre);
#if HDHAIR_FEATURE_MARSCHNER_TABLED || HDHAIR_FEATURE_MARSCHNER_ANALYTIC
#if HDHAIR_FEATURE_KAJIYA_KAY
        if (shading.model == 2) {
#endif
#if HDHAIR_FEATURE_MARSCHNER_TABLED && HDHAIR_FEATURE_MARSCHNER_ANALYTIC
            radiance += irradiance * (analytic ? marschnerAnalytic(t, l, e, shading.fibre)
                                               : marschnerTabled(t, l, e, marschnerTables, shading.tableLayer,
                                                                 shading.fibre.alpha, shading.fibre.beta));
#elif HDHAIR_FEATURE_MARSCHNER_ANALYTIC
            radiance += irradiance * marschnerAnalytic(t, l, e, shading.fibre);
#else
            radiance += irradiance * marschnerTabled(t, l, e, marschnerTables, shading.tableLayer, shading.fibre.alpha,
                                                     shading.fibre.beta);
#endif
#if HDHAIR_FEATURE_KAJIYA_KAY
            continue;
        }
#endif
#endif
#if HDHAIR_FEATURE_KAJIYA_KAY
        KajiyaKayTerms terms = kajiyaKay(t, l, e, shading.kajiyaKay.x, shading.kajiyaKay.y, shading.kajiyaKay.z);
        radiance += irradiance * (terms.diffuse * hairColor + terms.specular);
#endif
    }
    return radiance;
#else
    return vec3(0.0);  // every material of the frame is flat
#endif
}
