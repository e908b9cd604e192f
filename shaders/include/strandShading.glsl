// The radiance a strand fragment reflects towards the eye, by its prim's
// hair material: flat displayColor (look-dev, and tests whose pixels can be
// computed by hand), Kajiya-Kay, or Marschner with its azimuthal terms from
// tables or evaluated per fragment; lit by every light of the pass plus
// (first pass only) the dome's ambient or uniform term. SRBF lights of a
// dome read their material's convolution table (srbfLighting.glsl). Each
// light's irradiance is scaled by its shadow transmittance at the strand's
// centre line `centre`, or as strand.tese looked it up there with vertex
// shadows (the same for Kajiya-Kay and Marschner); the uniform dome's
// through the density volume where the plan says (uniformDomeVisibility),
// the flat ambient term never. `segment` and `u` locate the fragment on its
// span, for parameters that vary along the prim. Marschner materials with
// HAIR_MATERIAL_DUAL_SCATTERING add multiple scattering (dualScattering.glsl),
// from the same shadow transmittance.
// Needs frameUniforms.glsl, lights.glsl, kajiyaKay.glsl, marschner.glsl,
// marschnerAnalytic.glsl, dualScattering.glsl, catmullRom.glsl, hairMaterials.glsl,
// shadowFragmentLists.glsl, shadows.glsl and srbfLighting.glsl, after
// shadingFeatures.glsl, whose switches cut out what the frame does not use.
#ifdef HDHAIR_VERTEX_SHADOWS
// The pass's first HDHAIR_VERTEX_SHADOWS lights as strand.tese looked them
// up at the segment's ends, 4 a vec4, interpolated along it
// (shadowSampling=vertex); the lights after them have no map. Selected, not
// indexed, and no per-fragment lookup compiled at all: llvmpipe would run it
// masked anyway.
#ifdef HDHAIR_COMPUTE_RASTER
// strandRaster.comp sets them for each fragment, interpolated as the
// hardware rasteriser interpolates strand.geom's outputs.
vec4 vertexTransmittance[HDHAIR_VERTEX_SHADOW_VECTORS];
#else
layout(location = 6) in vec4 vertexTransmittance[HDHAIR_VERTEX_SHADOW_VECTORS];
#endif
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

// Dual scattering's densities (d_f, d_b) for light arriving from `toLight`:
// with the local term from the density volume, d_b times the share of the
// light passing the fibre that the hair behind it sends back, over a cone
// as wide as the back-scattered light's spread σ_b (Zinke 2008 eq. 17),
// held under 45°.
#if HDHAIR_FEATURE_DUAL_SCATTERING
vec2 dualScatteringDensitiesAt(vec2 densities, DualScatteringFibre fibre, vec3 centre, vec3 toLight) {
#if HDHAIR_FEATURE_VOLUME_BACK_SCATTERING
    if (shadows.occluders.z == 0) return densities;
    float spread = min(sqrt(max(dualScatteringMean(fibre.sigmaB2), 0.0)), 0.25 * MARSCHNER_PI);
    return vec2(densities.x, densities.y * densityVolumeBackOccupancy(centre, -toLight, tan(spread)));
#else
    return densities;
#endif
}
#endif

// What of the uniform dome (ambient.w 1) reaches a strand at `centre`, of
// unit tangent `t`: as
// the density volume lets it through (occluders.w), else all of it.
float uniformDomeVisibility(vec3 centre, vec3 t) {
#if HDHAIR_FEATURE_DENSITY_VOLUME
    if (shadows.occluders.w != 0 && lights.ambient.w > 0.5) return densityVolumeDomeVisibility(centre, t);
#endif
    return 1.0;
}

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
    vec3 dome = lights.ambient.rgb * uniformDomeVisibility(centre, t);
    vec3 radiance = lights.ambient.w > 0.5
                        ? dome * srbfUniformDomeResponse(materialIndex, shading, absorption, t, e, hairColor)
                        : lights.ambient.rgb * hairColor;
#else
    vec3 radiance = lights.ambient.rgb * hairColor;
#endif
    bool analytic = (shading.flags & HAIR_MATERIAL_ANALYTIC) != 0;
#if HDHAIR_FEATURE_DUAL_SCATTERING
    // Multiple scattering: the fibre's quantities at the eye's inclination
    // (as N_p is taken at theta_r), once a fragment; then each light adds
    // what its light scatters through the groom (dualScattering.glsl).
    bool dual = (shading.flags & HAIR_MATERIAL_DUAL_SCATTERING) != 0;
    DualScatteringFibre dualFibre;
    if (dual) {
        dualFibre = dualScatteringFibre(marschnerTables, shading.dualLayer, sqrt(max(0.0, 1.0 - dot(t, e) * dot(t, e))));
#if HDHAIR_FEATURE_UNIFORM_DOME
        // The dome's light that comes back to the eye arrived from its side.
        if (lights.ambient.w > 0.5)
            radiance += dome * dualScatteringUniformDome(dualFibre,
                                                  dualScatteringDensitiesAt(shading.dualDensities, dualFibre, centre, e));
#endif
    }
#endif
    for (int i = 0; i < lights.lightCount.x; ++i) {
#if HDHAIR_FEATURE_SRBF_LIGHTS
        if (isSrbfLight(i)) {
            vec3 lobe = srbfLightRadiance(i, materialIndex, shading, absorption, t, e, hairColor);
#if HDHAIR_FEATURE_DUAL_SCATTERING
            // The lobe as a distant light from its centre, its width added to
            // the first event's spread (Ren 2010 section 3.2; DualScattering.h).
            if (dual) {
                vec3 toLobe;
                vec3 lobeIrradiance = lightIrradiance(i, worldPosition, toLobe);
                float shadow = strandSrbfShadowTransmittance(i, centre);
                radiance += lobe * shadow +
                            lobeIrradiance * dualScattering(t, toLobe, e, dualFibre, shading.fibre.alpha,
                                                            shading.fibre.beta, shadow,
                                                            dualScatteringDensitiesAt(shading.dualDensities, dualFibre,
                                                                                      centre, toLobe),
                                                            0.25 / max(lights.lightScale[i].w, 1e-6));
                continue;
            }
#endif
            if (any(greaterThan(lobe, vec3(0.0)))) radiance += lobe * strandSrbfShadowTransmittance(i, centre);
            continue;
        }
#endif
        vec3 l;
        vec3 unshadowed = lightIrradiance(i, worldPosition, l);
        if (all(equal(unshadowed, vec3(0.0)))) continue;  // unlit here: no shadow lookup
        float shadow = strandShadowTransmittance(i, centre);
        vec3 irradiance = unshadowed * shadow;
#if HDHAIR_FEATURE_DUAL_SCATTERING
        if (dual)
            radiance += unshadowed * dualScattering(t, l, e, dualFibre, shading.fibre.alpha, shading.fibre.beta, shadow,
                                                    dualScatteringDensitiesAt(shading.dualDensities, dualFibre,
                                                                              centre, l),
                                                    0.0);
#endif
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
