#pragma once
// HdHairRenderPass: renders progressively, as hdEmbree does. On the host's
// thread _Execute gathers the camera, framing, AOV bindings, settings and a
// snapshot of the scene, hands them to its hdhair::ProgressiveRenderer (the
// engine renders on threads of its own, never the host's, whose GL context
// must stay current) and returns at once. Whenever the host executes the
// pass again (usdview every 5 ms, usdrecord and hdhair-record between short
// sleeps, while it is not converged) the newest finished image, a preview
// or the full frame, is copied into the bound render buffers, on the host's
// thread, so a buffer only ever holds a complete image. The pass and its buffers report
// converged once the full frame of the newest view is in. A frame whose
// inputs did not change is not asked for again. Bound id AOVs are rendered
// only once a host reads them (DeferredIds.h).

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "pxr/base/gf/matrix4d.h"
#include "pxr/base/gf/rect2i.h"
#include "pxr/imaging/hd/renderPass.h"

#include "hdHair/render/ProgressiveRenderer.h"

PXR_NAMESPACE_OPEN_SCOPE

class DeferredIds;
class HdHairRenderDelegate;
class HdHairRenderParam;

class HdHairRenderPass final : public HdRenderPass {
public:
    HdHairRenderPass(HdRenderIndex* index, HdRprimCollection const& collection, HdHairRenderDelegate* delegate,
                     HdHairRenderParam* renderParam);
    // Stops the frame in flight. Hydra destroys render passes (with the
    // task controller's tasks) before their delegate and its render param,
    // whose renderer the frames use.
    ~HdHairRenderPass() override;

    bool IsConverged() const override { return _converged; }

protected:
    void _Execute(HdRenderPassStateSharedPtr const& renderPassState, TfTokenVector const& renderTags) override;

private:
    // Where a frame's images go: equal layouts write the same buffers.
    struct Layout {
        std::vector<std::pair<SdfPath, HdRenderBuffer*>> buffers;
        std::vector<std::tuple<unsigned, unsigned, int>> bufferShapes;
        GfRect2i dataWindow;
        bool operator==(Layout const& other) const;
    };
    // Everything a frame depends on; equal keys mean an identical frame.
    struct FrameKey {
        uint64_t sceneVersion = 0;
        unsigned settingsVersion = 0;
        GfMatrix4d view, projection;
        Layout layout;
        TfTokenVector renderTags;
        bool operator==(FrameKey const& other) const;
    };

    // The key of the frame `state` asks for, into `dataWindow`.
    FrameKey _FrameKeyOf(HdRenderPassState const& state, TfTokenVector const& renderTags,
                         GfRect2i const& dataWindow) const;
    // Asks the renderer for `frame`; false when that failed (reported, and
    // the buffers cleared and settled).
    bool _SubmitFrame(FrameKey const& frame, HdRenderPassState const& state, TfTokenVector const& renderTags);
    // Shows the newest finished frame, if any, when it fits the buffers as
    // they are (`current`), and settles when it is the newest view's full frame.
    void _TakeFinished(Layout const& current, HdRenderPassAovBindingVector const& bindings);
    // Clears the bound buffers and copies a frame's images into them
    // (nothing more when `result` is null: a failed frame), compositing its
    // colour over the host's clear colour in place; id buffers the frame has
    // no ids for are left to `deferredIds`, when there is one.
    void _Write(hdhair::RenderResult* result, HdRenderPassAovBindingVector const& bindings,
                std::shared_ptr<DeferredIds> const& deferredIds = nullptr);
    // The pass and its buffers report converged: the newest view is in.
    void _Settle(HdRenderPassAovBindingVector const& bindings);
    // Reports a frame that cannot be rendered (TF_RUNTIME_ERROR, the render
    // stats) and clears the buffers; the caller settles.
    void _Fail(std::string const& why, HdRenderPassAovBindingVector const& bindings);

    HdHairRenderDelegate* _delegate;
    HdHairRenderParam* _renderParam;
    std::unique_ptr<hdhair::ProgressiveRenderer> _renderer;
    FrameKey _lastFrame;  // the newest request's
    bool _hasLastFrame = false;
    uint64_t _newestRequest = 0;
    // Requests whose images may still come: an older view's image is shown
    // while the newer one renders, if it fits the buffers.
    struct Requested {
        Layout layout;
        // The request again, for DeferredIds: when id AOVs are bound and the
        // frame was asked for without them.
        std::optional<hdhair::FrameRequest> deferredIdsRequest;
    };
    std::map<uint64_t, Requested> _requests;
    // Whether a host has read the ids of a frame: from then on every frame
    // renders them with its colour.
    bool _idsRead = false;
    std::shared_ptr<DeferredIds> _deferredIds;  // the newest frame's, if deferred
    bool _converged = false;
    std::string _shown = "none";  // what the buffers hold (RenderParam's Progress)
    std::string _error;           // why, when _shown is "failed"
    std::pair<int, int> _shownPreview{0, 0};  // the last preview shown: pixel divisor, curve stride
};

PXR_NAMESPACE_CLOSE_SCOPE
