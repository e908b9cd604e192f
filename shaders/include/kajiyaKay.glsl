// Kajiya-Kay hair shading (Kajiya & Kay 1989, "Rendering fur with three
// dimensional textures", section 3.1; Svoboda 2012 section 1.4.1).
// Must match hdHair/shading/KajiyaKay.h, which documents the parameters.
//   diffuse  = Kd / pi * sin(t, l)
//   specular = Ks / pi * cos^p(theta_e - theta_r), the eye's angle to the mirror
//              cone angle(t, r) = pi - angle(t, l):  cos = sin_tl sin_te - (t.l)(t.e)
// The 1/pi puts USD light units on the scale of physically based renderers:
// with Kd = 1 a fibre lit head-on reflects like a Lambertian surface of
// albedo displayColor.
// t: unit tangent; l: unit direction to the light; e: unit direction to the eye.
struct KajiyaKayTerms {
    float diffuse;
    float specular;
};

KajiyaKayTerms kajiyaKay(vec3 t, vec3 l, vec3 e, float Kd, float Ks, float p) {
    float tl = clamp(dot(t, l), -1.0, 1.0);
    float te = clamp(dot(t, e), -1.0, 1.0);
    // max() before sqrt: rounding can make 1 - x^2 slightly negative.
    float sinTl = sqrt(max(0.0, 1.0 - tl * tl));
    float sinTe = sqrt(max(0.0, 1.0 - te * te));
    float cosToCone = clamp(sinTl * sinTe - tl * te, 0.0, 1.0);
    KajiyaKayTerms terms;
    const float inversePi = 0.31830988618379067;
    terms.diffuse = Kd * inversePi * sinTl;
    terms.specular = Ks * inversePi * pow(cosToCone, max(p, 1.0));
    return terms;
}
