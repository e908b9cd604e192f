#pragma once
// DeferredIds: a frame's primId, instanceId and elementId images, rendered
// the first time a host reads one of them. HdxTaskController binds the id
// AOVs beside color for every renderer but Storm, so usdrecord and usdview
// always ask for them, yet read them only to pick or to highlight a
// selection (HdxColorizeSelectionTask returns before touching them when
// nothing is selected). Rendering them costs the ids pass and 12 bytes a
// pixel of GL images cleared and read back, a sizeable share of a large
// groom's frame on llvmpipe. So the render pass renders its
// frames without ids and leaves each bound id buffer one of these: the first
// Resolve() or Map() of any of them renders the same request again with ids
// (synchronously, on the host's thread, under the renderer's mutex), and
// every id buffer of the frame takes its image from that one render. Once a
// host has read ids, the pass asks for them with every frame (RenderPass.cpp).

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "pxr/base/tf/token.h"

#include "hdHair/render/ProgressiveRenderer.h"

PXR_NAMESPACE_OPEN_SCOPE

class DeferredIds {
public:
    // `renderer`, `rendererMutex` and `diagnostics` must outlive this (the
    // render param's; Hydra destroys render buffers before their delegate).
    DeferredIds(hdhair::Renderer& renderer, std::mutex& rendererMutex, hdhair::Diagnostics& diagnostics,
                hdhair::FrameRequest request);

    // The top-down image of `aov` (primId, instanceId or elementId): the
    // frame's ids, rendered on the first call. Empty when that render failed
    // (a runtime error says why).
    std::vector<int32_t> const& Ids(TfToken const& aov);

    // Whether a host has read them (the first Ids() call has happened).
    bool WereRead() const { return _read.load(); }

private:
    hdhair::Renderer& _renderer;
    std::mutex& _rendererMutex;
    hdhair::Diagnostics& _diagnostics;
    hdhair::FrameRequest _request;
    std::mutex _mutex;  // one render, whichever buffer asks first
    bool _rendered = false;
    std::atomic<bool> _read{false};
    std::vector<int32_t> _primIds, _instanceIds, _elementIds;
    std::vector<int32_t> const _none;
};

PXR_NAMESPACE_CLOSE_SCOPE
