// Kajiya-Kay hair shading (Kajiya & Kay 1989, "Rendering fur with three
// dimensional textures", section 3.1; Svoboda 2012 section 1.4.1).
// Must match hdHair/shading/KajiyaKay.h, which documents the parameters.
//   diffuse  = Kd sin(t, l)
//   specular = Ks cos^p(theta_e - theta_r), the eye's angle to the mirror cone
//              angle(t, r) = pi - angle(t, l):  cos = sin_tl sin_te - (t.l)(t.e)
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
    terms.diffuse = Kd * sinTl;
    terms.specular = Ks * pow(cosToCone, p);
    return terms;
}
