#pragma once
// A frame as a graph of passes (in the spirit of Filament's render graph):
// each pass declares the resources it reads and writes, the scene and the
// settings decide which passes are wanted, and compile() keeps only those
// whose output something downstream reads, back from what the frame
// delivers (its colour, depth and ids). The renderer then runs exactly the
// enabled passes, in declaration order; nothing else decides what runs.
//
// Resources are named: "preparedStrands" (an input from the CPU),
// "strands" (the GPU copy), "drawOrder", "color", "depth", "ids",
// "deepOpacity <light>", and so on. A pass that reads and writes the same
// resource (a light batch adding onto "color") updates it in place.

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace hdhair {

using FrameResource = std::string;

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
    Clear,
    Meshes,
    Strands,
    Ids,
    Resolve,
    LightBatch,
    Readback,
    DisplayTransform,
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
    static std::string reasonFor(const FramePass& pass);

    std::vector<FrameResource> inputs_, outputs_;
    std::vector<FramePass> passes_;
};

}  // namespace hdhair
