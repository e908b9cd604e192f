#include "hdHair/hydra/RenderPass.h"

#include <cstring>
#include <exception>
#include <optional>

#include "pxr/base/gf/camera.h"
#include "pxr/base/gf/frustum.h"
#include "pxr/base/gf/vec4f.h"
#include "pxr/base/tf/diagnostic.h"
#include "pxr/base/tf/stringUtils.h"
#include "pxr/imaging/cameraUtil/conformWindow.h"
#include "pxr/imaging/cameraUtil/framing.h"
#include "pxr/imaging/hd/camera.h"
#include "pxr/imaging/hd/renderPassState.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/CompositeOver.h"
#include "hdHair/hydra/DebugCodes.h"
#include "hdHair/hydra/DeferredIds.h"
#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/RenderBuffer.h"
#include "hdHair/hydra/RenderDelegate.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/scene/SceneValidation.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

HdHairRenderBuffer* colorBufferOf(HdRenderPassAovBindingVector const& bindings) {
    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.aovName == HdAovTokens->color) return static_cast<HdHairRenderBuffer*>(binding.renderBuffer);
    return nullptr;
}

bool wantsIds(HdRenderPassAovBindingVector const& bindings) {
    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.aovName == HdAovTokens->primId || binding.aovName == HdAovTokens->instanceId ||
            binding.aovName == HdAovTokens->elementId)
            return true;
    return false;
}

void setConverged(HdRenderPassAovBindingVector const& bindings, bool converged) {
    for (HdRenderPassAovBinding const& binding : bindings)
        if (binding.renderBuffer) static_cast<HdHairRenderBuffer*>(binding.renderBuffer)->SetConverged(converged);
}

// The host's camera prim as the engine's CameraPrim, in USD's authored
// units: UsdImaging hands focal length and apertures over in scene units
// (GfCamera's tenths), and the checks name the values the artist wrote.
hdhair::CameraPrim cameraPrimOf(HdCamera const& camera) {
    hdhair::CameraPrim prim;
    prim.path = camera.GetId().GetString();
    prim.projection = camera.GetProjection() == HdCamera::Orthographic ? hdhair::Projection::Orthographic
                                                                        : hdhair::Projection::Perspective;
    const float focalUnit = float(GfCamera::FOCAL_LENGTH_UNIT), apertureUnit = float(GfCamera::APERTURE_UNIT);
    prim.focalLength = camera.GetFocalLength() / focalUnit;
    prim.horizontalAperture = camera.GetHorizontalAperture() / apertureUnit;
    prim.verticalAperture = camera.GetVerticalAperture() / apertureUnit;
    prim.horizontalApertureOffset = camera.GetHorizontalApertureOffset() / apertureUnit;
    prim.verticalApertureOffset = camera.GetVerticalApertureOffset() / apertureUnit;
    prim.clippingRange = {camera.GetClippingRange().GetMin(), camera.GetClippingRange().GetMax()};
    prim.worldTransform = hdhair::hydra::matrixFromGf(camera.GetTransform().data());
    return prim;
}

// The projection the host would have made had the camera carried `lens`'s
// (repaired) clipping range: HdCamera::ComputeProjectionMatrix's frustum,
// then HdRenderPassState::GetProjectionMatrix's framing or conformed window.
// The host's own matrix cannot be patched: with near equal to far its depth
// terms are infinite, and the framing's product has spread NaN from them.
GfMatrix4d projectionFor(hdhair::CameraPrim const& lens, HdRenderPassState const& state) {
    GfCamera camera;
    camera.SetProjection(lens.projection == hdhair::Projection::Orthographic ? GfCamera::Orthographic
                                                                              : GfCamera::Perspective);
    camera.SetFocalLength(lens.focalLength);
    camera.SetHorizontalAperture(lens.horizontalAperture);
    camera.SetVerticalAperture(lens.verticalAperture);
    camera.SetHorizontalApertureOffset(lens.horizontalApertureOffset);
    camera.SetVerticalApertureOffset(lens.verticalApertureOffset);
    camera.SetClippingRange(GfRange1f(lens.clippingRange[0], lens.clippingRange[1]));
    const GfMatrix4d projection = camera.GetFrustum().ComputeProjectionMatrix();
    if (state.GetFraming().IsValid()) return state.GetFraming().ApplyToProjectionMatrix(projection, state.GetWindowPolicy());
    GfVec4f const& viewport = state.GetViewport();
    return CameraUtilConformedWindow(projection, state.GetWindowPolicy(),
                                     viewport[3] != 0.0f ? double(viewport[2]) / double(viewport[3]) : 1.0);
}

// Matrices compared bit for bit: a host's NaN matrix (a camera with near
// equal to far) is the same view from one execute to the next, not a new
// one each time, which would render and warn again without end.
bool sameBits(GfMatrix4d const& a, GfMatrix4d const& b) {
    return std::memcmp(a.data(), b.data(), sizeof(double) * 16) == 0;
}

// Where the image goes (y down): the framing's data window; without a
// framing, the legacy viewport.
GfRect2i dataWindowOf(HdRenderPassState const& state) {
    CameraUtilFraming const& framing = state.GetFraming();
    if (framing.IsValid()) return framing.dataWindow;
    GfVec4f const& viewport = state.GetViewport();
    return GfRect2i(GfVec2i(int(viewport[0]), int(viewport[1])), int(viewport[2]), int(viewport[3]));
}

// The host's camera as the engine's view of `dataWindow`, its lens and
// transform checked as the embedded reader checks them.
hdhair::CameraView cameraViewOf(HdCamera const& camera, HdRenderPassState const& state, GfMatrix4d const& view,
                                GfMatrix4d const& hostProjection, GfRect2i const& dataWindow,
                                hdhair::Diagnostics& diagnostics) {
    // A lens that cannot be used is an error naming the prim and attribute,
    // a bad clipping range takes USD's fallback with a warning.
    const hdhair::CameraPrim prim = cameraPrimOf(camera);
    const hdhair::CameraPrim checked = hdhair::checkedCamera(prim, "the host's camera", diagnostics);
    const GfMatrix4d projection =
        checked.clippingRange == prim.clippingRange ? hostProjection : projectionFor(checked, state);
    return hdhair::hydra::cameraViewFromHydra(view.data(), projection.data(), dataWindow.GetWidth(),
                                              dataWindow.GetHeight());
}

}  // namespace

bool HdHairRenderPass::Layout::operator==(Layout const& other) const {
    return buffers == other.buffers && bufferShapes == other.bufferShapes && dataWindow == other.dataWindow;
}

bool HdHairRenderPass::FrameKey::operator==(FrameKey const& other) const {
    return sceneVersion == other.sceneVersion && settingsVersion == other.settingsVersion &&
           sameBits(view, other.view) && sameBits(projection, other.projection) && layout == other.layout &&
           renderTags == other.renderTags;
}

HdHairRenderPass::HdHairRenderPass(HdRenderIndex* index, HdRprimCollection const& collection,
                                   HdHairRenderDelegate* delegate, HdHairRenderParam* renderParam)
    : HdRenderPass(index, collection), _delegate(delegate), _renderParam(renderParam) {}

HdHairRenderPass::~HdHairRenderPass() = default;

HdHairRenderPass::FrameKey HdHairRenderPass::_FrameKeyOf(HdRenderPassState const& state,
                                                          TfTokenVector const& renderTags,
                                                          GfRect2i const& dataWindow) const {
    FrameKey frame;
    frame.sceneVersion = _renderParam->GetSceneVersion();
    frame.settingsVersion = _delegate->GetRenderSettingsVersion();
    frame.view = state.GetWorldToViewMatrix();
    frame.projection = state.GetProjectionMatrix();
    frame.layout.dataWindow = dataWindow;
    for (HdRenderPassAovBinding const& binding : state.GetAovBindings()) {
        frame.layout.buffers.emplace_back(binding.renderBufferId, binding.renderBuffer);
        if (binding.renderBuffer)
            frame.layout.bufferShapes.emplace_back(binding.renderBuffer->GetWidth(), binding.renderBuffer->GetHeight(),
                                                   int(binding.renderBuffer->GetFormat()));
    }
    frame.renderTags = renderTags;
    return frame;
}

bool HdHairRenderPass::_SubmitFrame(FrameKey const& frame, HdRenderPassState const& state,
                                    TfTokenVector const& renderTags) {
    HdRenderPassAovBindingVector const& bindings = state.GetAovBindings();
    try {
        if (!_renderer)
            _renderer = std::make_unique<hdhair::ProgressiveRenderer>(
                _renderParam->GetRenderer(), _renderParam->GetRendererMutex(), _renderParam->GetDiagnostics());
        hdhair::FrameRequest request;
        int refineLevel = 0;
        request.scene = _renderParam->Snapshot(renderTags, &refineLevel);
        request.settings = _delegate->GetEngineSettings();
        request.settings.setComplexity(hdhair::hydra::complexityFromRefineLevel(refineLevel));
        request.camera = cameraViewOf(*state.GetCamera(), state, frame.view, frame.projection, frame.layout.dataWindow,
                                      _renderParam->GetDiagnostics());
        Requested requested{frame.layout, std::nullopt};
        request.ids = wantsIds(bindings) && _idsRead;
        if (wantsIds(bindings) && !request.ids) requested.deferredIdsRequest = request;
        _newestRequest = _renderer->submit(std::move(request));
        _requests[_newestRequest] = std::move(requested);
    } catch (std::exception const& error) {
        // No GL, say: reported once per change and the buffers left
        // cleared; hosts must not hang waiting for a frame that cannot come.
        _Fail(error.what(), bindings);
        _newestRequest = 0;
        _requests.clear();
        _renderParam->SetProgress({_shown, _error, false, 0, 0, 0, 0, 0});
        _Settle(bindings);
        return false;
    }
    return true;
}

void HdHairRenderPass::_Execute(HdRenderPassStateSharedPtr const& renderPassState,
                                TfTokenVector const& renderTags) {
    HdRenderPassAovBindingVector const& bindings = renderPassState->GetAovBindings();
    HdHairRenderBuffer* colorBuffer = colorBufferOf(bindings);
    if (!colorBuffer || !renderPassState->GetCamera()) {
        // Nothing to render into, or nothing to render from: done, so that
        // hosts waiting for convergence do not wait forever.
        _converged = true;
        return;
    }

    const FrameKey frame = _FrameKeyOf(*renderPassState, renderTags, dataWindowOf(*renderPassState));
    if (_deferredIds && _deferredIds->WereRead()) _idsRead = true;
    if (!_hasLastFrame || !(frame == _lastFrame)) {
        _lastFrame = frame;
        _hasLastFrame = true;
        _converged = false;
        setConverged(bindings, false);
        if (!_SubmitFrame(frame, *renderPassState, renderTags)) return;
    }

    _TakeFinished(frame.layout, bindings);
    if (_renderer) {
        hdhair::ProgressiveRenderer::Counts const counts = _renderer->counts();
        _renderParam->SetProgress({_shown, _error, _renderer->rendering() != 0, counts.previews, counts.finals,
                                   counts.cancelled, _shownPreview.first, _shownPreview.second});
    }
}

void HdHairRenderPass::_TakeFinished(Layout const& current, HdRenderPassAovBindingVector const& bindings) {
    std::optional<hdhair::FinishedFrame> finished = _renderer ? _renderer->takeFinished() : std::nullopt;
    if (!finished) return;
    // Requests older than this one will send nothing more (this one may
    // still send its full frame after a preview).
    auto requested = _requests.find(finished->request);
    const bool fits = requested != _requests.end() && requested->second.layout == current;
    std::optional<hdhair::FrameRequest> deferredIdsRequest;
    // Copied, not moved: a preview and its full frame share the request
    // (the scene's prims are shared, so the copy is cheap).
    if (fits) deferredIdsRequest = requested->second.deferredIdsRequest;
    _requests.erase(_requests.begin(), _requests.lower_bound(finished->request));
    // An older view's image is shown while the newest renders, unless the
    // buffers changed since it was asked for.
    if (!fits) return;
    const bool final = finished->quality == hdhair::FrameQuality::Final;
    if (!finished->error.empty()) {
        _Fail(finished->error, bindings);
    } else {
        _error.clear();
        hdhair::RenderResult& result = finished->result;
        // testUsdview reads the full frame's line: keep its form.
        std::string const what =
            final ? std::string("frame")
                  : TfStringPrintf("preview (1/%d of the pixels across, every %d. curve)", finished->previewDivisor,
                                   finished->previewCurveStride);
        TF_DEBUG(HDHAIR_FRAMES)
            .Msg("hdHair: rendered a %s: %dx%d, %llu curves, %llu segments, %s, %.1f ms\n", what.c_str(),
                 result.color.width, result.color.height, static_cast<unsigned long long>(result.stats.curves),
                 static_cast<unsigned long long>(result.stats.segments), result.stats.transparency.c_str(),
                 finished->milliseconds);
        if (final) _renderParam->SetLastFrame(result.stats.toJson().dump(), result.describePlans());
        _deferredIds = nullptr;
        if (deferredIdsRequest && result.primIds.empty())
            _deferredIds = std::make_shared<DeferredIds>(_renderParam->GetRenderer(), _renderParam->GetRendererMutex(),
                                                         _renderParam->GetDiagnostics(),
                                                         std::move(*deferredIdsRequest));
        _Write(&result, bindings, _deferredIds);
        _shown = hdhair::toString(finished->quality);
        if (!final) _shownPreview = {finished->previewDivisor, finished->previewCurveStride};
    }
    if (final && finished->request == _newestRequest) _Settle(bindings);
}

void HdHairRenderPass::_Fail(std::string const& why, HdRenderPassAovBindingVector const& bindings) {
    // The error reaches the host through Tf and the render stats
    // (hdHairShownFrame "failed", hdHairFrameError): hosts such as usdrecord
    // render until the pass reports converged, so a failed frame converges
    // too (with cleared buffers) rather than keep them waiting forever.
    TF_RUNTIME_ERROR("hdHair: the frame could not be rendered: %s", why.c_str());
    _Write(nullptr, bindings);
    _shown = "failed";
    _error = why;
}

void HdHairRenderPass::_Settle(HdRenderPassAovBindingVector const& bindings) {
    setConverged(bindings, true);
    _converged = true;
}

void HdHairRenderPass::_Write(hdhair::RenderResult* result, HdRenderPassAovBindingVector const& bindings,
                              std::shared_ptr<DeferredIds> const& deferredIds) {
    HdHairRenderBuffer* colorBuffer = colorBufferOf(bindings);
    const int bufferWidth = int(colorBuffer->GetWidth()), bufferHeight = int(colorBuffer->GetHeight());
    GfRect2i const& dataWindow = _lastFrame.layout.dataWindow;
    hdhair::hydra::DataWindow window{dataWindow.GetMinX(), dataWindow.GetMinY(), dataWindow.GetWidth(),
                                     dataWindow.GetHeight()};
    for (HdRenderPassAovBinding const& binding : bindings) {
        auto* buffer = static_cast<HdHairRenderBuffer*>(binding.renderBuffer);
        if (!buffer || int(buffer->GetWidth()) != bufferWidth || int(buffer->GetHeight()) != bufferHeight) continue;
        hdhair::hydra::BufferFormat format;
        if (!buffer->GetWritableFormat(&format)) continue;
        buffer->Clear(binding.clearValue);
        buffer->SetDeferredIds(nullptr, TfToken(), window);
        if (!result) continue;
        if (binding.aovName == HdAovTokens->color) {
            // Empty pixels show the host's clear colour (usdview's
            // background): the frame is composited over it.
            GfVec4f clear = binding.clearValue.IsHolding<GfVec4f>() ? binding.clearValue.UncheckedGet<GfVec4f>()
                                                                     : GfVec4f(0.0f);
            // In place: the result is this pass's to consume, and a copy of
            // a 1280-pixel frame's colour is 19 MB of memory touched afresh.
            hdhair::hydra::compositeOver(result->color, {clear[0], clear[1], clear[2], clear[3]});
            hdhair::hydra::writeImageToBuffer(result->color, format, window, bufferWidth, bufferHeight,
                                              buffer->GetData());
        } else if (binding.aovName == HdAovTokens->depth) {
            hdhair::hydra::writeImageToBuffer(result->depth, format, window, bufferWidth, bufferHeight,
                                              buffer->GetData());
        } else if (format == hdhair::hydra::BufferFormat::Int32) {
            std::vector<int32_t> const* ids = binding.aovName == HdAovTokens->primId       ? &result->primIds
                                              : binding.aovName == HdAovTokens->instanceId ? &result->instanceIds
                                              : binding.aovName == HdAovTokens->elementId  ? &result->elementIds
                                                                                           : nullptr;
            if (!ids) continue;
            if (ids->empty() && deferredIds) buffer->SetDeferredIds(deferredIds, binding.aovName, window);
            else hdhair::hydra::writeIdsToBuffer(*ids, window, bufferWidth, bufferHeight, buffer->GetData());
        }
    }
}

PXR_NAMESPACE_CLOSE_SCOPE
