#include "hdHair/hydra/DeferredIds.h"

#include <exception>
#include <utility>

#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/hd/tokens.h"

PXR_NAMESPACE_OPEN_SCOPE

DeferredIds::DeferredIds(hdhair::Renderer& renderer, std::mutex& rendererMutex, hdhair::Diagnostics& diagnostics,
                         hdhair::FrameRequest request)
    : _renderer(renderer), _rendererMutex(rendererMutex), _diagnostics(diagnostics), _request(std::move(request)) {
    _request.ids = true;
}

std::vector<int32_t> const& DeferredIds::Ids(TfToken const& aov) {
    std::lock_guard<std::mutex> lock(_mutex);
    if (!_rendered) {
        _rendered = true;
        _read.store(true);
        try {
            std::lock_guard<std::mutex> rendering(_rendererMutex);
            // The full frame's settings and camera, whether the host shows
            // that frame or a preview of it: ids of the finished view.
            hdhair::RenderResult result = _renderer.render(_request.scene, _request.camera, _request.settings,
                                                           _diagnostics, hdhair::RenderOutputs{true},
                                                           hdhair::FrameControl{});
            _primIds = std::move(result.primIds);
            _instanceIds = std::move(result.instanceIds);
            _elementIds = std::move(result.elementIds);
        } catch (std::exception const& error) {
            TF_RUNTIME_ERROR("hdHair: the frame's ids could not be rendered: %s", error.what());
        }
    }
    if (aov == HdAovTokens->primId) return _primIds;
    if (aov == HdAovTokens->instanceId) return _instanceIds;
    if (aov == HdAovTokens->elementId) return _elementIds;
    return _none;
}

PXR_NAMESPACE_CLOSE_SCOPE
