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

#include "hdHair/gl/MeshPass.h"
#include "hdHair/gl/UniformBlocks.h"
#include "hdHair/image/DisplayShader.h"
#include "hdHair/render/BinSort.h"
#include "hdHair/render/CameraView.h"
#include "hdHair/render/RenderPlan.h"
#include "hdHair/render/StrandUploads.h"

namespace hdhair {

class Diagnostics;
class RenderSettings;
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
    std::vector<const std::vector<uint16_t>*> tables;
    int tableWidth = 1, tableHeight = 1;
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
    const RenderSettings* settings = nullptr;
    bool idsRequested = false;
    bool depthRequested = true;
    const DisplayShader* gpuDisplay = nullptr;  // the displayTransform pass's shader
    bool displayOverBlack = false;
    std::vector<DrawnPrim> drawn;            // visible prims, in draw order
    StrandUploadPlan uploads;                // their GPU ranges and what to send
    std::vector<SortSpan> sortSpans;         // their segments for the bin sort
    std::optional<MaterialUpload> materials;
    MeshUpload meshes;
    gl::FrameUniforms frame;
    int samples = 0;                         // multisampling the driver gives
    size_t fragmentListCapacity = 0;         // exact transparency's budget, in fragments
};

struct FrameContext {
    FrameInputs& inputs;
    RenderPlan& plan;
    FrameResources& resources;
    Diagnostics& diagnostics;
    RenderResult& result;
    std::vector<uint32_t> drawOrder;         // the sort's output
    gl::RenderTarget* target = nullptr;      // set by the clear pass
    bool shadowPoolEmptied = false;          // shadowMode=reference: the pool was emptied this frame
    std::vector<std::string> unshadowed;     // lights whose shadow could not be built (warned)
};

// Runs one pass of the plan. Throws std::logic_error for a pass it does not know.
void runFramePass(const FramePass& pass, FrameContext& context);

// The passes that run on the CPU (timed by the CPU clock).
bool isCpuPass(const FramePass& pass);

}  // namespace hdhair
