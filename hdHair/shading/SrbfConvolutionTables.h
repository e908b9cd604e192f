#pragma once
// The SRBF-convolution tables: for one material, the radiance a
// fibre scatters towards ωo under one SRBF lobe of unit amplitude
// (SrbfConvolution.h), precomputed over the lobe's centre and bandwidth and
// the view, for the GPU to sample once per lobe and fragment.
// Ren, Zhou, Li, Hua & Guo 2010, §3 and eq. (4): the integral
//   I(ωo; ξ, λ) = ∫ G(ωi; ξ, λ) S(ωi, ωo) cos θ_i dωi
// depends on the geometry only through the fibre-frame angles, so it is a
// 4-D table I(θ_ξ, θ_o, φ_ξ − φ_o, 1/λ) (the paper's I_M; for Kajiya-Kay its
// I_d and I_s, which do not depend on the azimuth).
//
// Axes (all sampled at grid nodes that include both ends):
//   ψ   = |φ_o − φ_ξ| ∈ [0, π]     the paper indexes cos ψ; uniform ψ keeps
//         the resolution where TT's forward peak is (ψ = π): uniform cos ψ
//         has a first step of √(2·2/N) rad there (20° at N = 32). The table
//         is even in ψ (N_p and G are), so ψ ∈ [0, π] is all of it.
//   θ_o ∈ [−π/2, π/2], θ_ξ ∈ [−π/2, π/2]   the signed inclinations from the
//         normal plane (sin θ = t·ω). Signed, because the cuticle tilts α_p
//         make Marschner's response asymmetric in θ, which cos θ (the
//         paper's index) loses. Uniform in θ, not in sin θ: N_p, η' and
//         κ = λ cos θ_i cos θ_ξ are smooth in θ but have a square-root edge
//         in sin θ at grazing (MarschnerTables.h measured 10× the error for
//         sin θ_r on that account).
//   1/λ ∈ [1/64, 1/16]            Ren §3: the convolution is close to linear
//         in the lobe's angular variance 1/λ.
//
// How the table is built (in seconds, not the paper's 50 min): exactly
// factored, with no separability approximation. In the fibre frame
//   G = exp(λ(cos(θ_i − θ_ξ) − 1)) · exp(κ(cos Δ − 1)),  κ = λ cos θ_i cos θ_ξ,
// Δ = φ_i − φ_ξ (exact: ωi·ξ = sin θ_i sin θ_ξ + cos θ_i cos θ_ξ cos Δ). N_p
// depends on φ = φ_o − φ_i = ψ − Δ and θ_o only (Marschner.h), so with its
// cosine series N_p(φ) = a_p0/2 + Σ_n a_pn cos nφ and A&S 9.6.19,
//   ∫ exp(κ(cos Δ − 1)) cos(n(ψ − Δ)) dΔ = 2π e^(−κ) I_n(κ) cos nψ,
// the azimuthal integral is a product per Fourier mode, and
//   I = Σ_p Σ_n a'_pn(θ_o) cos nψ · B_pn(θ_o, θ_ξ, λ),   a'_p0 = a_p0/2,
//   B_pn = ∫ cos θ_i M_p(θ_i, θ_o) exp(λ(cos(θ_i − θ_ξ) − 1)) 2π e^(−κ) I_n(κ) dθ_i.
// Orders n ≤ 64 (e^(−κ)I_n(κ)/e^(−κ)I_0(κ) < e^(−32) at κ ≤ 64); a_pn by the
// midpoint rule on 1024 azimuths of [0, π]; B_pn by the midpoint rule on 360
// inclinations (0.5°: M_p's narrowest lobe at β's 0.5° floor has σ = 1°).
// Kajiya-Kay keeps only n = 0 (its f does not depend on φ). TBB runs one task
// per (θ_ξ, 1/λ) slice; each writes its own texels in a fixed order, so the
// table is bit-identical for any thread count.
//
// Channels (what colour factors out of):
//   MarschnerColour: RGB radiance, σ_a, η, α_p, β_p, k_G and the caustic
//                    parameters baked in (absorption does not factor out).
//   MarschnerLobes:  (R, TT, TRT) at σ_a = 0, the fallback for prims whose
//                    absorption varies (SrbfVaryingAbsorption.h).
//   KajiyaKay:       (diffuse, specular) for Kd = Ks = 1: both terms are
//                    linear in Kd·colour and Ks, so a 2-channel scalar table
//                    per shininess p serves every colour; azimuth size 1.
//
// GPU layout (the flat `texels` array as glTexImage3D takes it):
//   GL_TEXTURE_3D, GL_RGB16F (Half) or GL_RGB32F (Float) for the Marschner
//   kinds, GL_RG16F / GL_RG32F for Kajiya-Kay; GL_LINEAR min and mag, no
//   mipmaps, GL_CLAMP_TO_EDGE on s, t, r.
//   width  W = azimuths       x ↔ ψ node x = ψ_x = π x/(W − 1)
//   height H = outgoing       y ↔ θ_o node y = −π/2 + π y/(H − 1)
//   depth  D = centres × bandwidths: z = l·centres + k, slab l ↔ 1/λ node
//          1/λ_l = 1/64 + (1/16 − 1/64) l/(bandwidths − 1), k ↔ θ_ξ node
//          −π/2 + π k/(centres − 1)
//   texel (x, y, z) starts at float index ((z·H + y)·W + x)·channels and holds
//   the value at its nodes. glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB16F, W, H, D,
//   0, GL_RGB, GL_HALF_FLOAT, table.halfTexels().data()).
// The shader's lookup, per fragment and lobe (sampleSrbfTable does the same
// on the CPU):
//   θ_o = asin(clamp(t·ωo)), θ_ξ = asin(clamp(t·ξ)),
//   ψ = atan2(|p_o × p_ξ|, p_o·p_ξ) with p = ω − (t·ω)t (0 when either is 0),
//   u_ψ = ψ/π·(W−1), u_o = (θ_o/π + ½)(H−1), u_ξ = (θ_ξ/π + ½)(centres−1),
//   u_λ = (1/λ − 1/64)/(1/16 − 1/64)·(bandwidths−1), each clamped to
//   [0, size − 1]; l0 = floor(u_λ), l1 = min(l0 + 1, bandwidths − 1);
//   for l in {l0, l1}: texture(table, vec3((u_ψ + ½)/W, (u_o + ½)/H,
//   (l·centres + u_ξ + ½)/D)), and mix the two by u_λ − l0. The hardware
//   interpolates ψ, θ_o, θ_ξ (u_ξ stays within its slab, so slabs never
//   bleed into each other); the shader interpolates 1/λ: two fetches per lobe.
//   Multiply by the lobe's amplitude L_j (and T̃_j); for Kajiya-Kay,
//   Kd·colour·.r + Ks·.g.
//
// Resolution, memory, build time and the measured error against
// SrbfConvolution.h: hdHair/shading/README.md, "SRBF-convolution tables".

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/environment/Srbf.h"

namespace hdhair {

enum class SrbfTableKind : std::uint32_t { MarschnerColour = 1, MarschnerLobes = 2, KajiyaKay = 3 };
enum class SrbfTablePrecision : std::uint32_t { Half = 1, Float = 2 };

struct SrbfTableResolution {
    int azimuths = 32;   // W, ψ nodes (1 for Kajiya-Kay)
    int outgoing = 64;   // H, θ_o nodes
    int centres = 64;    // θ_ξ nodes per slab
    int bandwidths = 8;  // slabs, 1/λ nodes
    bool operator==(const SrbfTableResolution& other) const;
};

// The defaults: README "SRBF-convolution tables" has the measurements behind them.
constexpr SrbfTablePrecision kSrbfTablePrecision = SrbfTablePrecision::Half;
SrbfTableResolution defaultSrbfTableResolution(SrbfTableKind kind);

struct SrbfConvolutionTable {
    SrbfTableKind kind = SrbfTableKind::MarschnerColour;
    SrbfTableResolution resolution;
    SrbfTablePrecision precision = SrbfTablePrecision::Half;
    int channels = 3;  // 3 for the Marschner kinds, 2 for Kajiya-Kay
    // Layout above; already rounded to half when precision is Half, so CPU
    // lookups see what the GPU sees.
    std::vector<float> texels;

    int width() const { return resolution.azimuths; }
    int height() const { return resolution.outgoing; }
    int depth() const { return resolution.centres * resolution.bandwidths; }
    // The texels as IEEE half floats for glTexImage3D(…, GL_HALF_FLOAT, …).
    std::vector<std::uint16_t> halfTexels() const;
    // What the texture takes on the GPU (2 or 4 bytes per channel).
    std::size_t gpuBytes() const;
};

// Sizes below 2 count as 2 (the azimuth of Kajiya-Kay is always 1).
SrbfConvolutionTable buildSrbfMarschnerTable(const MarschnerParameters& parameters,
                                             const SrbfTableResolution& resolution =
                                                 defaultSrbfTableResolution(SrbfTableKind::MarschnerColour),
                                             SrbfTablePrecision precision = kSrbfTablePrecision);
// (R, TT, TRT) with σ_a = 0 (parameters.sigmaA is ignored).
SrbfConvolutionTable buildSrbfMarschnerLobeTable(const MarschnerParameters& parameters,
                                                 const SrbfTableResolution& resolution =
                                                     defaultSrbfTableResolution(SrbfTableKind::MarschnerLobes),
                                                 SrbfTablePrecision precision = kSrbfTablePrecision);
// (diffuse, specular) for Kd = Ks = 1 and the given shininess p.
SrbfConvolutionTable buildSrbfKajiyaKayTable(float shininess,
                                             const SrbfTableResolution& resolution =
                                                 defaultSrbfTableResolution(SrbfTableKind::KajiyaKay),
                                             SrbfTablePrecision precision = kSrbfTablePrecision);

// The fibre-frame angles the tables are indexed by, as the shader computes them.
struct SrbfTableAngles {
    float thetaO = 0.0f;    // θ_o ∈ [−π/2, π/2]
    float thetaXi = 0.0f;   // θ_ξ ∈ [−π/2, π/2]
    float psi = 0.0f;       // |φ_o − φ_ξ| ∈ [0, π]
    float bandwidth = kMinSrbfBandwidth;  // λ
};
SrbfTableAngles srbfTableAngles(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe);

// The lookup the shader does (above): trilinear at texel centres with clamp
// to edge in (ψ, θ_o, θ_ξ), linear in 1/λ between two slabs. Channels past
// table.channels are 0.
glm::vec3 sampleSrbfTable(const SrbfConvolutionTable& table, const SrbfTableAngles& angles);

// A MarschnerColour table: the RGB radiance per unit lobe amplitude.
glm::vec3 evaluateSrbfMarschnerTable(const SrbfConvolutionTable& table, const glm::vec3& t, const glm::vec3& wo,
                                     const SrbfLobe& lobe);
// A KajiyaKay table: the terms with Kd and Ks applied (diffuse multiplies the
// hair colour), as convolveSrbfKajiyaKay returns them.
KajiyaKayTerms evaluateSrbfKajiyaKayTable(const SrbfConvolutionTable& table, const glm::vec3& t, const glm::vec3& wo,
                                          const SrbfLobe& lobe, const KajiyaKayParameters& parameters);

}  // namespace hdhair
