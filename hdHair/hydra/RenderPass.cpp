#include "hdHair/hydra/RenderPass.h"

#include <exception>

#include "pxr/base/gf/vec4f.h"
#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/cameraUtil/framing.h"
#include "pxr/imaging/hd/renderPassState.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/CompositeOver.h"
#include "hdHair/hydra/DebugCodes.h"
#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/RenderBuffer.h"
#include "hdHair/hydra/RenderDelegate.h"
#include "hdHair/hydra/RenderParam.h"

PXR_NAMESPACE_OPEN_SCOPE

bool HdHairRenderPass::FrameKey::operator==(FrameKey const& other) const {
    return sceneVersion == other.sceneVersion && settingsVersion == other.settingsVersion && view == other.view &&
           projection == other.projection && dataWindow == other.dataWindow && buffers == other.buffers &&
           bufferShapes == other.bufferShapes && renderTags == other.renderTags;
}

HdHairRenderPass::HdHairRenderPass(HdRenderIndex* index, HdRprimCollection const& collection,
                                   HdHairRenderDelegate* delegate, HdHairRenderParam* renderParam)
    : HdRenderPass(index, collection), _delegate(delegate), _renderParam(renderParam) {}

void HdHairRenderPass::_Execute(HdRenderPassStateSharedPtr const& renderPassState,
                                TfTokenVector const& renderTags) {
    HdRenderPassAovBindingVector const& bindings = renderPassState->GetAovBindings();
    HdHairRenderBuffer* colorBuffer = nullptr;
    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.aovName == HdAovTokens->color) colorBuffer = static_cast<HdHairRenderBuffer*>(binding.renderBuffer);
    if (!colorBuffer || !renderPassState->GetCamera()) {
        // Nothing to render into, or nothing to render from: done, so that
        // hosts waiting for convergence do not wait forever.
        _converged = true;
        return;
    }
    int bufferWidth = int(colorBuffer->GetWidth()), bufferHeight = int(colorBuffer->GetHeight());

    // The framing's data window is where the image goes (y down); without a
    // framing, the legacy viewport.
    CameraUtilFraming const& framing = renderPassState->GetFraming();
    GfRect2i dataWindow;
    if (framing.IsValid()) {
        dataWindow = framing.dataWindow;
    } else {
        GfVec4f const& viewport = renderPassState->GetViewport();
        dataWindow = GfRect2i(GfVec2i(int(viewport[0]), int(viewport[1])), int(viewport[2]), int(viewport[3]));
    }

    FrameKey frame;
    frame.sceneVersion = _renderParam->GetSceneVersion();
    frame.settingsVersion = _delegate->GetRenderSettingsVersion();
    frame.view = renderPassState->GetWorldToViewMatrix();
    frame.projection = renderPassState->GetProjectionMatrix();
    frame.dataWindow = dataWindow;
    for (HdRenderPassAovBinding const& binding : bindings) {
        frame.buffers.emplace_back(binding.renderBufferId, binding.renderBuffer);
        if (binding.renderBuffer)
            frame.bufferShapes.emplace_back(binding.renderBuffer->GetWidth(), binding.renderBuffer->GetHeight(),
                                            int(binding.renderBuffer->GetFormat()));
    }
    frame.renderTags = renderTags;
    if (_hasLastFrame && frame == _lastFrame && _converged) return;

    _converged = false;
    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.renderBuffer) static_cast<HdHairRenderBuffer*>(binding.renderBuffer)->SetConverged(false);

    hdhair::hydra::DataWindow window{dataWindow.GetMinX(), dataWindow.GetMinY(), dataWindow.GetWidth(),
                                     dataWindow.GetHeight()};
    bool wantIds = false;
    for (HdRenderPassAovBinding const& binding : bindings)
        wantIds = wantIds || binding.aovName == HdAovTokens->primId || binding.aovName == HdAovTokens->instanceId ||
                  binding.aovName == HdAovTokens->elementId;

    try {
        int refineLevel = 0;
        hdhair::Scene scene = _renderParam->Snapshot(renderTags, &refineLevel);
        hdhair::RenderSettings settings = _delegate->GetEngineSettings();
        settings.setComplexity(hdhair::hydra::complexityFromRefineLevel(refineLevel));
        hdhair::CameraView camera = hdhair::hydra::cameraViewFromHydra(frame.view.data(), frame.projection.data(),
                                                                        window.width, window.height);
        hdhair::RenderResult result = _renderParam->GetRenderer().render(
            scene, camera, settings, _renderParam->GetDiagnostics(), hdhair::RenderOutputs{wantIds});
        _renderParam->SetLastFrame(result.stats.toJson().dump(), result.plan.describe());
        TF_DEBUG(HDHAIR_FRAMES)
            .Msg("hdHair: rendered a frame: %dx%d, %llu curves, %llu segments, %s, %.1f ms\n", camera.imageWidth,
                 camera.imageHeight, static_cast<unsigned long long>(result.stats.curves),
                 static_cast<unsigned long long>(result.stats.segments), result.stats.transparency.c_str(),
                 result.stats.totalMilliseconds);

        for (HdRenderPassAovBinding const& binding : bindings) {
            auto* buffer = static_cast<HdHairRenderBuffer*>(binding.renderBuffer);
            if (!buffer || int(buffer->GetWidth()) != bufferWidth || int(buffer->GetHeight()) != bufferHeight) continue;
            hdhair::hydra::BufferFormat format;
            if (!buffer->GetWritableFormat(&format)) continue;
            buffer->Clear(binding.clearValue);
            if (binding.aovName == HdAovTokens->color) {
                // Empty pixels show the host's clear colour (usdview's
                // background): the frame is composited over it.
                GfVec4f clear = binding.clearValue.IsHolding<GfVec4f>() ? binding.clearValue.UncheckedGet<GfVec4f>()
                                                                         : GfVec4f(0.0f);
                hdhair::Image color = result.color;
                hdhair::hydra::compositeOver(color, {clear[0], clear[1], clear[2], clear[3]});
                hdhair::hydra::writeImageToBuffer(color, format, window, bufferWidth, bufferHeight, buffer->GetData());
            } else if (binding.aovName == HdAovTokens->depth) {
                hdhair::hydra::writeImageToBuffer(result.depth, format, window, bufferWidth, bufferHeight,
                                                  buffer->GetData());
            } else if (wantIds && format == hdhair::hydra::BufferFormat::Int32) {
                std::vector<int32_t> const* ids = binding.aovName == HdAovTokens->primId       ? &result.primIds
                                                  : binding.aovName == HdAovTokens->instanceId ? &result.instanceIds
                                                  : binding.aovName == HdAovTokens->elementId  ? &result.elementIds
                                                                                               : nullptr;
                if (ids) hdhair::hydra::writeIdsToBuffer(*ids, window, bufferWidth, bufferHeight, buffer->GetData());
            }
        }
    } catch (std::exception const& error) {
        // A failed frame is reported once per change and left cleared; hosts
        // must not hang waiting for it.
        TF_RUNTIME_ERROR("hdHair: the frame could not be rendered: %s", error.what());
    }

    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.renderBuffer) static_cast<HdHairRenderBuffer*>(binding.renderBuffer)->SetConverged(true);
    _lastFrame = frame;
    _hasLastFrame = true;
    _converged = true;
}

PXR_NAMESPACE_CLOSE_SCOPE
