#pragma once
// Kajiya-Kay hair shading on the CPU: the same formula as
// shaders/include/kajiyaKay.glsl, used by tests and as its documentation.
//
// Kajiya & Kay 1989, "Rendering fur with three dimensional textures", §3.1;
// Svoboda 2012, §1.4.1. A fibre is an infinitely thin cylinder with tangent t.
//   diffuse:  Kd/π · sin(t, l)                (Lambert integrated over the lit half of the cylinder)
//   specular: Ks/π · cos^p(θe − θr)           θr: the mirror cone, angle(t, r) = π − angle(t, l)
//             cos(θe − θr) = sin(t,l)·sin(t,e) − (t·l)(t·e)
// The 1/π is Lambert's normalisation: with Kd = 1, a fibre lit head-on by a
// light of irradiance E reflects E·displayColor/π, as a Lambertian surface of
// that albedo does in physically based renderers (RenderMan, Arnold, Karma),
// so USD light intensities mean the same thing in hdHair as beside them.
// l points towards the light, e towards the eye. The outgoing radiance from a
// light of irradiance E is E·(diffuse·hairColour + specular): the specular
// highlight is white, as on a dielectric fibre surface.

#include <glm/vec3.hpp>

namespace hdhair {

// Defaults chosen for dark-to-mid brown hair under USD's light units: a
// diffuse weight of 1 lets displayColor act as the fibre's albedo, and a
// specular of 0.35 with exponent 60 gives the narrow, dimmer highlight
// typical of hair. All three are render settings (kajiyaKay:diffuse,
// kajiyaKay:specular, kajiyaKay:shininess).
struct KajiyaKayParameters {
    float diffuse = 1.0f;    // Kd, >= 0
    float specular = 0.35f;  // Ks, >= 0
    float shininess = 60.0f; // p, >= 1
};

struct KajiyaKayTerms {
    float diffuse = 0.0f;   // in [0, Kd/π]
    float specular = 0.0f;  // in [0, Ks/π]
};

// t, l and e need not be normalised; zero vectors are treated as
// perpendicular to everything, so the result stays finite and bounded.
KajiyaKayTerms evaluateKajiyaKay(const glm::vec3& t, const glm::vec3& l, const glm::vec3& e,
                                 const KajiyaKayParameters& parameters);

}  // namespace hdhair
