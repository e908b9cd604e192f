#pragma once
// Which parts of the strand shading a draw can reach (decided from the
// frame's plan and materials: hdHair/render/StrandShadingFeatures.h), and
// the GLSL that compiles only those parts (it replaces shaders/include/shadingFeatures.glsl, whose
// switches this mirrors). Why: llvmpipe runs a fragment shader as masked
// SIMD and pays for every branch whether a fragment takes it or not, so a
// Kajiya-Kay frame with one deep-opacity light ran the Marschner, SRBF and
// reference-shadow code too (docs/performance.md has what
// compiling only the reachable code saves). A feature is on whenever the draw could take its
// branch, so a specialised program draws exactly what the complete one
// draws (testShaderSpecialization).

#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

enum class ShadingFeature : uint32_t {
    Shade = 1u << 0,                // colour is written (not the ids pass)
    KajiyaKay = 1u << 1,            // a material of model 1
    MarschnerTabled = 1u << 2,      // a Marschner material reading its tables
    MarschnerAnalytic = 1u << 3,    // a Marschner material evaluated per fragment
    PerPointParameters = 1u << 4,   // a material whose parameters vary per curve or vertex
    SrbfAbsorption = 1u << 5,       // a Marschner material with absorption per fragment under a dome
    DualScattering = 1u << 15,      // a Marschner material with multiple scattering
    LocalLights = 1u << 6,          // a light with a position
    SrbfLights = 1u << 7,           // a dome's SRBF lobe
    UniformDome = 1u << 8,          // the uniform dome's exact response
    DeepOpacity = 1u << 9,          // deep opacity maps, a light of the draw having one
    ShadowReference = 1u << 10,     // the reference shadows' fragment lists, likewise
    MeshOccluders = 1u << 11,       // meshes' depth in the light views
    BilinearShadows = 1u << 14,     // four texels a lookup (shadowFilter=bilinear), not one
    SrbfShadowTaps = 1u << 12,      // a lobe with a map, nine taps (domeShadowFilter=taps)
    SrbfShadowMipmap = 1u << 13,    // a lobe with a map, the mip chain (domeShadowFilter=mipmap)
    DensityVolume = 1u << 16,       // a light or the uniform dome through the hair's density volume
    VolumeBackScattering = 1u << 17,  // dual scattering's local term from the density volume
};

class ShadingFeatures {
public:
    ShadingFeatures() = default;
    static ShadingFeatures all();  // what the file compiles as it stands

    bool has(ShadingFeature feature) const { return (bits_ & uint32_t(feature)) != 0; }
    ShadingFeatures& add(ShadingFeature feature) {
        bits_ |= uint32_t(feature);
        return *this;
    }
    ShadingFeatures& add(ShadingFeatures features) {
        bits_ |= features.bits_;
        return *this;
    }
    uint32_t bits() const { return bits_; }

    // The deep opacity maps' layer count (shadowLayers), compiled in as a
    // constant (shaders/include/shadows.glsl): up to 4 layers are looked up
    // in straight code with the layers in one vec4, where the uniform count
    // needs a loop over an array that llvmpipe keeps in memory, which is
    // slower. 0: read from the uniform
    // (ShadowUniforms::mode.y), as the complete program does.
    ShadingFeatures& setShadowLayers(int layers) {
        shadowLayers_ = layers;
        return *this;
    }
    int shadowLayers() const { return shadowLayers_; }

    // Deep opacity lookups at the tessellated points instead of per fragment
    // (shadowSampling=vertex): strand.tese looks up the pass's first
    // `lights` lights (0: none, per fragment) at each point of the centre
    // line, where the fragment lookup is taken too, and the fragments
    // interpolate the transmittance along the segment. Not a switch cutting
    // out a branch: it changes what is drawn, so the complete program takes
    // it as well. Compiled in as HDHAIR_VERTEX_SHADOWS, the light count (and
    // HDHAIR_VERTEX_SHADOW_VECTORS, the vec4s holding them), which the file
    // as it stands leaves undefined: the light views, which write the maps,
    // never read them.
    ShadingFeatures& setVertexShadowLights(int lights) {
        vertexShadowLights_ = lights;
        return *this;
    }
    int vertexShadowLights() const { return vertexShadowLights_; }

    // Strands drawn as one-pixel lines instead of ribbons (the light views'
    // shadowStrandLines, when no strand is over 1.5 texels wide): the
    // program has no geometry shader (ShadingPrograms leaves strand.geom
    // out), strand.tese (or strandChord.vert, for spans left one segment)
    // hands its lines straight to the rasteriser with the fragment stage's
    // inputs, and scales each point's alpha so that a line, one pixel along
    // its minor axis, holds the coverage of a ribbon of the strand's width
    // (strandLinePoint.glsl). Like vertex shadows it changes what is drawn, so
    // the complete program takes it too. Compiled in as HDHAIR_STRAND_LINES.
    ShadingFeatures& setStrandLines(bool lines) {
        strandLines_ = lines;
        return *this;
    }
    bool strandLines() const { return strandLines_; }

    // What tells one program from another: the switches, the layer count,
    // where shadows are looked up and whether strands are lines.
    uint64_t key() const {
        return uint64_t(bits_) | (uint64_t(uint32_t(shadowLayers_)) << 32) |
               (uint64_t(uint32_t(vertexShadowLights_)) << 48) | (uint64_t(strandLines_ ? 1 : 0) << 62);
    }
    bool operator==(const ShadingFeatures& other) const { return key() == other.key(); }
    bool operator!=(const ShadingFeatures& other) const { return key() != other.key(); }

    // The replacement of include/shadingFeatures.glsl: every switch defined,
    // 1 for the features held and 0 for the rest, HDHAIR_SHADOW_LAYERS when
    // the layer count is set, HDHAIR_VERTEX_SHADOWS with vertex shadows and
    // HDHAIR_STRAND_LINES with lines.
    std::string glsl() const;
    // The features held, by name ("kajiyaKay deepOpacity"), or "none"; then
    // "shadowLayers=N" when the count is set, "vertexShadows=N" and
    // "strandLines".
    std::string describe() const;

private:
    uint32_t bits_ = 0;
    int shadowLayers_ = 0;
    int vertexShadowLights_ = 0;
    bool strandLines_ = false;
};

// Every switch: its feature, its GLSL macro and the name describe() uses.
struct ShadingFeatureSwitch {
    ShadingFeature feature;
    const char* macro;
    const char* name;
};
const std::vector<ShadingFeatureSwitch>& shadingFeatureSwitches();

}  // namespace hdhair::gl
