#pragma once
// What each pass of the frame graph (RenderPlan.h) does on the GL thread.
// The renderer gathers everything a frame needs on the CPU first
// (FrameInputs); FrameScheduler then runs the plan's enabled passes in order,
// each through runFramePass().

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/HairMaterialTable.h"
#include "hdHair/gl/MeshPass.h"
#include "hdHair/gl/ShadingFeatures.h"
#include "hdHair/gl/UniformBlocks.h"
#include "hdHair/image/DisplayShader.h"
#include "hdHair/render/BinSort.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/FrameCancellation.h"
#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/render/SrbfMaterialTables.h"
#include "hdHair/render/StrandUploads.h"

namespace hdhair {

class Diagnostics;
struct PreparedMesh;
struct FrameResources;
struct RenderResult;

namespace gl {
class RenderTarget;
}

// The frame's hair materials as the GPU holds them (gl::HairMaterialTable),
// sent only when they changed.
struct MaterialUpload {
    std::vector<gl::GpuHairMaterial> materials;
    std::vector<glm::vec4> parameterPoints;
    std::vector<gl::MaterialTableLayers> tables;
    int tableWidth = 1, tableHeight = 1;
    // Dome lighting's tables (empty without a dome: 1-texel placeholders).
    SrbfTableUpload srbfTables;
};

// The frame's meshes as the GPU draws them: one range of the mesh buffer
// each, all sent again when `changed`.
struct MeshUpload {
    std::vector<std::shared_ptr<const PreparedMesh>> meshes;  // drawn, in draw order
    std::vector<gl::MeshDraw> draws;                           // their ranges and ids
    size_t vertices = 0;
    bool changed = false;
};

// Everything a frame's passes need, gathered on the CPU before any GL work.
struct FrameInputs {
    const CameraView* camera = nullptr;
    bool idsRequested = false;
    bool depthRequested = true;
    const DisplayShader* gpuDisplay = nullptr;  // the displayTransform pass's shader
    bool displayOverBlack = false;
    std::vector<DrawnPrim> drawn;            // visible prims, in draw order
    StrandUploadPlan uploads;                // their GPU ranges and what to send
    std::vector<SortSpan> sortSpans;         // their segments for the bin sort
    std::optional<MaterialUpload> materials;
    // The shading the frame's materials call for (materialShadingFeatures).
    gl::ShadingFeatures materialFeatures;
    MeshUpload meshes;
    gl::FrameUniforms frame;
    int samples = 0;                         // multisampling the driver gives
    size_t fragmentListCapacity = 0;         // exact transparency's budget, in fragments
    size_t computeRasterCapacity = 0;        // the compute rasteriser's, in fragments
};

struct FrameContext {
    FrameInputs& inputs;
    const RenderPlan& plan;
    FrameResources& resources;
    Diagnostics& diagnostics;
    RenderResult& result;
    std::vector<uint32_t> drawOrder;         // the sort's output
    gl::RenderTarget* target = nullptr;      // set by the clear pass
    bool shadowPoolEmptied = false;          // shadowMode=reference: the pool was emptied this frame
    // Lights whose map this frame was to build and did not: it needed more
    // memory than GL gives (warned), or the frame stopped before its passes
    // ran. The renderer forgets them, so the next frame builds them again.
    std::vector<std::string> unbuiltShadowMaps;
    // Polled between passes and between pieces of the strand draws; null:
    // the frame runs to its end, its strands drawn at once.
    const FrameCancellation* cancellation = nullptr;
    size_t strandPieceSegments = 0;  // segments per piece when cancellable
    bool stopped = false;            // the cancellation was seen: the rest of the frame is skipped
    // Why the frame cannot be rendered as asked (exact transparency over its
    // memory under exactOverflow=fail); the frame stops as a cancelled one
    // does, and the renderer throws this instead of FrameCancelled.
    std::string failure = {};
    // What a pass found that makes the plan impossible (FrameFallback.h); the
    // frame stops as a cancelled one does, and the renderer plans it again.
    std::optional<FrameFallback> fallback = {};
    // Each pass's time, by index into the plan's passes (with timing on).
    std::vector<double> passMilliseconds = {};
    // The pass running (FrameScheduler), and whether what its code touches
    // is checked against what it declares (FrameControl::checkResourceAccess).
    const FramePass* pass = nullptr;
    bool checkAccess = false;
};

// Runs one pass of the plan. Throws std::logic_error for a pass it does not know.
void runFramePass(const FramePass& pass, FrameContext& context);

// Whether the frame has been asked to stop (FrameCancellation.h); once it
// has, it stays stopped.
bool stopRequested(FrameContext& context);

// The passes a stopped frame still runs: the uploads, whose data the
// renderer counted as on the GPU when it planned them (StrandUploads,
// the material table, the mesh buffer).
bool runsWhenStopped(const FramePass& pass);

// The planned shadow (ShadowPlan::lights) whose map a pass builds
// ("shadowDepth L" and the other map passes), or nothing.
std::optional<size_t> shadowMapBuiltBy(const FramePass& pass);

// The passes that run on the CPU (timed by the CPU clock).
bool isCpuPass(const FramePass& pass);

}  // namespace hdhair
