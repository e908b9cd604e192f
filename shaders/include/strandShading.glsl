// The radiance a strand fragment reflects towards the eye: flat displayColor
// (look-dev, and tests whose pixels can be computed by hand) or Kajiya-Kay
// lit by every light in the pass plus the dome's ambient term.
// Needs frameUniforms.glsl, lights.glsl and kajiyaKay.glsl.
vec3 strandRadiance(vec3 worldPosition, vec3 worldTangent, vec3 hairColor) {
    if (frame.shadingModel == 0) return hairColor;
    vec3 t = normalize(worldTangent);
    vec3 e = directionToEye(worldPosition);
    vec3 radiance = lights.ambient.rgb * hairColor;
    vec3 kk = lights.kajiyaKayParameters.xyz;
    for (int i = 0; i < lights.lightCount.x; ++i) {
        vec3 l;
        vec3 irradiance = lightIrradiance(i, worldPosition, l);
        KajiyaKayTerms terms = kajiyaKay(t, l, e, kk.x, kk.y, kk.z);
        radiance += irradiance * (terms.diffuse * hairColor + terms.specular);
    }
    return radiance;
}
