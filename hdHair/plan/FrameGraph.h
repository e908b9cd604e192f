#pragma once
// A frame as a graph of passes (in the spirit of Filament's render graph):
// each pass declares the resources it reads and writes, the scene and the
// settings decide which passes are wanted, and compile() keeps only those
// whose output something downstream reads, back from what the frame
// delivers (its colour, depth and ids). The renderer then runs exactly the
// enabled passes, in declaration order; nothing else decides what runs.
//
// Resources are typed: a kind and, for the kinds each shadow-casting light
// has one of, the index of its planned shadow (ShadowPlan::lights), after
// Filament's FrameGraphId. A pass that reads and writes the same resource
// (a light batch adding onto the colour) updates it in place. Each pass's
// code checks what it touches against what its pass declares
// (FramePasses.cpp, FrameAccess), so a declaration cannot drift from the
// code unseen.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/base/TokenTable.h"

namespace hdhair {

enum class ResourceKind {
    PreparedStrands,   // the drawn prims' curves on the CPU (an input)
    PreparedMeshes,    // the drawn meshes on the CPU (an input)
    Strands,           // the strands on the GPU, with their materials
    MeshGeometry,      // the meshes on the GPU
    DrawOrder,         // the bin sort's segment order
    HairDepth,         // per light: the nearest hair in its view
    DeepOpacity,       // per light: its opacity layers
    ShadowFragments,   // per light: every light-view fragment (shadowMode=reference)
    MeshDepth,         // per light: the nearest mesh in its view
    ConvolvedOpacity,  // every map's opacity layers as a mip chain
    DensityVolume,     // the hair's optical density on a grid (HairDensityGrid.h)
    Color,
    Depth,
    Ids,
    Aovs,              // the frame's images on the CPU
    DisplayImage,      // the display image made on the GPU
};
template <>
struct TokenTable<ResourceKind> {
    static constexpr std::array<TokenName<ResourceKind>, 16> names{{
        {ResourceKind::PreparedStrands, "preparedStrands"},
        {ResourceKind::PreparedMeshes, "preparedMeshes"},
        {ResourceKind::Strands, "strands"},
        {ResourceKind::MeshGeometry, "meshGeometry"},
        {ResourceKind::DrawOrder, "drawOrder"},
        {ResourceKind::HairDepth, "hairDepth"},
        {ResourceKind::DeepOpacity, "deepOpacity"},
        {ResourceKind::ShadowFragments, "shadowFragments"},
        {ResourceKind::MeshDepth, "meshDepth"},
        {ResourceKind::ConvolvedOpacity, "convolvedOpacity"},
        {ResourceKind::DensityVolume, "densityVolume"},
        {ResourceKind::Color, "color"},
        {ResourceKind::Depth, "depth"},
        {ResourceKind::Ids, "ids"},
        {ResourceKind::Aovs, "aovs"},
        {ResourceKind::DisplayImage, "displayImage"},
    }};
};

// Whether each light has a resource of this kind (indexed by its planned shadow).
constexpr bool isPerLight(ResourceKind kind) {
    return kind == ResourceKind::HairDepth || kind == ResourceKind::DeepOpacity ||
           kind == ResourceKind::ShadowFragments || kind == ResourceKind::MeshDepth;
}

struct FrameResource {
    ResourceKind kind;
    size_t light = 0;  // per-light kinds: the planned shadow (ShadowPlan::lights); else 0

    FrameResource(ResourceKind resourceKind, size_t shadow = 0)
        : kind(resourceKind), light(isPerLight(resourceKind) ? shadow : 0) {}
    bool operator==(const FrameResource& other) const { return kind == other.kind && light == other.light; }
    bool operator!=(const FrameResource& other) const { return !(*this == other); }
    bool operator<(const FrameResource& other) const {
        return kind != other.kind ? kind < other.kind : light < other.light;
    }
};

// What a pass does. The renderer runs a pass by its kind (FramePasses.cpp
// has one function per kind, named as the kind is in --explain: a pass
// "deepOpacity /World/key" runs deepOpacity()); the pass's name is only its
// label.
enum class PassKind {
    Upload,
    MeshUpload,
    Sort,
    ShadowDepth,
    DeepOpacity,
    ShadowFragments,
    MeshShadow,
    OpacityMipmaps,
    DensityVolume,
    Clear,
    Meshes,
    Strands,
    Ids,
    Resolve,
    LightBatch,
    Readback,
    DisplayTransform,
};
// Each kind's name: its passes' labels begin with it ("deepOpacity /World/key").
template <>
struct TokenTable<PassKind> {
    static constexpr std::array<TokenName<PassKind>, 17> names{{
        {PassKind::Upload, "upload"},
        {PassKind::MeshUpload, "meshUpload"},
        {PassKind::Sort, "sort"},
        {PassKind::ShadowDepth, "shadowDepth"},
        {PassKind::DeepOpacity, "deepOpacity"},
        {PassKind::ShadowFragments, "shadowFragments"},
        {PassKind::MeshShadow, "meshShadow"},
        {PassKind::OpacityMipmaps, "opacityMipmaps"},
        {PassKind::DensityVolume, "densityVolume"},
        {PassKind::Clear, "clear"},
        {PassKind::Meshes, "meshes"},
        {PassKind::Strands, "strands"},
        {PassKind::Ids, "ids"},
        {PassKind::Resolve, "resolve"},
        {PassKind::LightBatch, "lightBatch"},
        {PassKind::Readback, "readback"},
        {PassKind::DisplayTransform, "displayTransform"},
    }};
};

struct FramePass {
    PassKind kind;
    std::string name;                  // "strands", "lightBatch 2", "shadowDepth /World/key"
    std::vector<FrameResource> reads;  // what it needs, written by earlier passes or inputs
    std::vector<FrameResource> writes;
    bool wanted = false;               // the scene and settings call for it
    std::string reason;                // why it is wanted, or why not
    bool enabled = false;              // wanted, and its output is read: it runs (compile())
    // What the pass works on: its light batch (LightBatch, from 0), or its
    // light's planned shadow (the shadow-map kinds: ShadowPlan::lights).
    size_t subject = 0;
};

class FrameGraph {
public:
    // Declares a resource that comes from outside the graph (prepared curves).
    void input(const FrameResource& resource);
    // The names of the lights per-light resources are indexed by, for
    // --explain and --stats ("deepOpacity /World/key").
    void nameLights(std::vector<std::string> names) { lightNames_ = std::move(names); }
    // "color", "deepOpacity /World/key".
    std::string nameOf(const FrameResource& resource) const;
    std::vector<std::string> namesOf(const std::vector<FrameResource>& resources) const;
    // Declares a pass; passes run in the order they are added.
    FramePass& add(FramePass pass);
    // What the frame delivers: passes that (transitively) feed these run.
    void output(const FrameResource& resource);

    // Decides which wanted passes run: walking back from the outputs, a
    // wanted pass is enabled when a later enabled pass or an output reads
    // something it writes. Throws std::logic_error when an enabled pass
    // reads a resource that neither an input nor an earlier enabled pass
    // provides (a wiring mistake, never bad input).
    void compile();

    // Once compiled, the graph is read only: a frame runs it as it is.
    const std::vector<FramePass>& passes() const { return passes_; }
    const std::vector<FrameResource>& inputs() const { return inputs_; }
    const std::vector<FrameResource>& outputs() const { return outputs_; }
    // By label (--explain's names: tests and tools).
    const FramePass* find(const std::string& name) const;
    bool isEnabled(const std::string& name) const;
    // By kind and subject (what the renderer uses).
    const FramePass* find(PassKind kind, size_t subject = 0) const;
    bool isEnabled(PassKind kind, size_t subject = 0) const;

    // One line per pass: on/off, reads -> writes, reason.
    std::string describe() const;
    // With each enabled pass's time when `milliseconds` has one per pass
    // (FrameScheduler measures them; the graph does not keep them).
    nlohmann::json toJson(const std::vector<double>& milliseconds = {}) const;

private:
    // The pass's reason, and for a wanted pass that is not built, why not.
    std::string reasonFor(const FramePass& pass) const;
    std::string joined(const std::vector<FrameResource>& resources) const;

    std::vector<FrameResource> inputs_, outputs_;
    std::vector<FramePass> passes_;
    std::vector<std::string> lightNames_;
};

}  // namespace hdhair
