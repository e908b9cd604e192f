#pragma once
// hdHair's Marschner parameters as Cycles' Principled Hair BSDF (Chiang,
// Bitterli, Tappan & Burley 2016, "A Practical and Controllable Hair and Fur
// Model for Production Path Tracing"), parametrised by absorption
// coefficient. docs/cycles-reference.md ("Fibre model") has the table of
// what maps exactly and what cannot.
//
//  - σ_a: the same quantity in both (per unit fibre radius, along the chord
//    2 cos γ_t / cos θ_t; Chiang eq. 5 after pbrt-v4), passed through.
//  - η: the same index of refraction.
//  - Longitudinal roughness: hdHair's d'Eon lobe for R has variance
//    v_R = (2β_R)² (Marschner.h); Chiang eq. 7 gives Cycles' v from its
//    roughness β_m: v = (0.726β_m + 0.812β_m² + 3.7β_m²⁰)². So β_m is the
//    root of 0.726β_m + 0.812β_m² + 3.7β_m²⁰ = 2β_R in [0, 1] (clamped).
//    Both then take v/4 for TT and 4v for TRT, Marschner's Table 1 ratios
//    that hdHair derives its TT and TRT widths with.
//  - Cuticle tilt: Cycles' offset α shifts R by 2α, TT by −α and TRT by −4α
//    (Chiang §4.1, after d'Eon 2011); hdHair shifts R by 2α_R, TT by −α_R and
//    TRT by −3α_R (Marschner Table 1). The R lobe is matched: α = −α_R, since
//    Cycles measures the tilt towards the root as positive where Marschner's
//    α_R is negative (checked by the fibre calibration test); TRT then sits
//    α_R/2 away from hdHair's.
//  - Azimuthal roughness β_n: hdHair's N_p is Marschner's smooth fibre with
//    the caustic's glint lobes; Chiang's is a logistic of scale s(β_n). No β_n
//    makes them equal. kCyclesRadialRoughness is used, documented with its
//    measured effect.
//  - Chiang's residual lobe (p ≥ 3) and coat have no hdHair counterpart:
//    coat is 0, the residual lobe cannot be switched off in Cycles.

#include <glm/vec3.hpp>

#include "hdHair/shading/Marschner.h"

namespace hdhair {

// β_n of the reference's fibres: Cycles' default, and the azimuthal
// roughness hdHair's colour-to-absorption inversion assumes
// (marschnerSigmaAFromColor).
constexpr float kCyclesRadialRoughness = 0.3f;

struct PrincipledHair {
    glm::vec3 absorption{0.0f};  // σ_a
    float roughness = 0.3f;      // β_m
    float radialRoughness = kCyclesRadialRoughness;
    float ior = 1.55f;
    float offset = 0.0f;         // α (radians)
    float coat = 0.0f;
};

// Chiang's β_m whose R-lobe variance equals hdHair's for width β_R (radians).
float principledHairRoughness(float betaR);

PrincipledHair principledHairFrom(const MarschnerParameters& marschner);

}  // namespace hdhair
