// The radiance a strand fragment reflects towards the eye, by its prim's
// hair material: flat displayColor (look-dev, and tests whose pixels can be
// computed by hand), Kajiya-Kay, or Marschner with tabled azimuthal terms;
// lit by every light of the pass plus (first pass only) the dome's ambient.
// Needs frameUniforms.glsl, lights.glsl, kajiyaKay.glsl, marschner.glsl and
// hairMaterials.glsl.
vec3 strandRadiance(vec3 worldPosition, vec3 worldTangent, vec3 hairColor, int materialIndex) {
    HairMaterial material = materials[materialIndex];
    int model = material.modelAndLayer.x;
    if (model == 0) return hairColor;
    vec3 t = normalize(worldTangent);
    vec3 e = directionToEye(worldPosition);
    vec3 radiance = lights.ambient.rgb * hairColor;
    for (int i = 0; i < lights.lightCount.x; ++i) {
        vec3 l;
        vec3 irradiance = lightIrradiance(i, worldPosition, l);
        if (model == 2) {
            radiance += irradiance * marschnerTabled(t, l, e, marschnerTables, float(material.modelAndLayer.y),
                                                     material.alpha.xyz, material.beta.xyz);
        } else {
            KajiyaKayTerms terms =
                kajiyaKay(t, l, e, material.kajiyaKay.x, material.kajiyaKay.y, material.kajiyaKay.z);
            radiance += irradiance * (terms.diffuse * hairColor + terms.specular);
        }
    }
    return radiance;
}
