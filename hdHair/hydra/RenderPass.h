#pragma once
// HdHairRenderPass: renders one frame synchronously. On the host's thread it
// gathers the camera, framing, lights (already in the scene), AOV bindings
// and settings; the engine renders on its own GL thread (never the host's,
// whose GLX context must stay current); then the pixels go into the bound
// render buffers, which report converged. A frame whose inputs did not change
// is not rendered again.

#include <string>

#include "pxr/base/gf/matrix4d.h"
#include "pxr/base/gf/rect2i.h"
#include "pxr/imaging/hd/renderPass.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairRenderDelegate;
class HdHairRenderParam;

class HdHairRenderPass final : public HdRenderPass {
public:
    HdHairRenderPass(HdRenderIndex* index, HdRprimCollection const& collection, HdHairRenderDelegate* delegate,
                     HdHairRenderParam* renderParam);
    ~HdHairRenderPass() override = default;

    bool IsConverged() const override { return _converged; }

protected:
    void _Execute(HdRenderPassStateSharedPtr const& renderPassState, TfTokenVector const& renderTags) override;

private:
    // Everything a frame depends on; equal keys mean an identical frame.
    struct FrameKey {
        uint64_t sceneVersion = 0;
        unsigned settingsVersion = 0;
        GfMatrix4d view, projection;
        GfRect2i dataWindow;
        std::vector<std::pair<SdfPath, HdRenderBuffer*>> buffers;
        std::vector<std::tuple<unsigned, unsigned, int>> bufferShapes;
        TfTokenVector renderTags;
        bool operator==(FrameKey const& other) const;
    };

    HdHairRenderDelegate* _delegate;
    HdHairRenderParam* _renderParam;
    FrameKey _lastFrame;
    bool _hasLastFrame = false;
    bool _converged = false;
};

PXR_NAMESPACE_CLOSE_SCOPE
