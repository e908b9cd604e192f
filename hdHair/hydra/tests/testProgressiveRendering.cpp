// Progressive rendering through UsdImagingGL, driven as usdview and usdrecord
// drive the plugin (hdHair/hydra/RenderPass.h): one Render call per timer
// tick until the engine reports converged. A new view is not converged until
// its full frame is in, the full frame after a preview is the image a host
// without previews gets, and a camera move stops the full frame in flight
// and ends on the new view's image.

#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "pxr/base/gf/half.h"
#include "pxr/base/gf/rect2i.h"
#include "pxr/base/plug/registry.h"
#include "pxr/base/vt/dictionary.h"
#include "pxr/imaging/cameraUtil/framing.h"
#include "pxr/imaging/hd/renderBuffer.h"
#include "pxr/imaging/hd/tokens.h"
#include "pxr/usd/usd/stage.h"
#include "pxr/usd/usdGeom/basisCurves.h"
#include "pxr/usd/usdGeom/camera.h"
#include "pxr/usd/usdGeom/xformable.h"
#include "pxr/usd/usdLux/distantLight.h"
#include "pxr/usdImaging/usdImagingGL/engine.h"

#include "CpuEngineParameters.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace {

TfToken const kPluginId("HdHairRendererPlugin");

class HydraProgressiveRendering : public ::testing::Test {
protected:
    static void SetUpTestSuite() { PlugRegistry::GetInstance().RegisterPlugins(HDHAIR_PLUGIN_RESOURCES); }
};

// A camera on the z axis looking down -Z at a field of `curves` wavy,
// half-opaque catmullRom strands in the plane z = 0 (x and y in [-2, 2]),
// lit by a distant light that casts shadows (USD's default).
UsdStageRefPtr wavyFieldStage(int curves) {
    UsdStageRefPtr stage = UsdStage::CreateInMemory();
    UsdGeomCamera camera = UsdGeomCamera::Define(stage, SdfPath("/Camera"));
    camera.AddTranslateOp().Set(GfVec3d(0, 0, 10));
    UsdLuxDistantLight light = UsdLuxDistantLight::Define(stage, SdfPath("/Light"));
    light.CreateIntensityAttr(VtValue(2.0f));
    light.AddRotateXYZOp().Set(GfVec3f(-30.0f, 20.0f, 0.0f));
    VtIntArray counts;
    VtVec3fArray points;
    for (int c = 0; c < curves; ++c) {
        const float x = -2.0f + 4.0f * std::fmod(0.618034f * float(c), 1.0f);
        const float z = -0.5f + std::fmod(0.414214f * float(c), 1.0f);
        counts.push_back(8);
        for (int p = 0; p < 8; ++p) {
            const float t = float(p) / 7.0f;
            points.push_back(GfVec3f(x + 0.2f * std::sin(7.0f * t + float(c)), -2.0f + 4.0f * t, z));
        }
    }
    UsdGeomBasisCurves strands = UsdGeomBasisCurves::Define(stage, SdfPath("/Hair"));
    strands.CreateTypeAttr(VtValue(UsdGeomTokens->cubic));
    strands.CreateBasisAttr(VtValue(UsdGeomTokens->catmullRom));
    strands.CreateCurveVertexCountsAttr(VtValue(counts));
    strands.CreatePointsAttr(VtValue(points));
    strands.CreateWidthsAttr(VtValue(VtFloatArray{0.01f}));
    strands.CreateDisplayColorPrimvar(UsdGeomTokens->constant).Set(VtVec3fArray{GfVec3f(0.7f, 0.5f, 0.3f)});
    strands.CreateDisplayOpacityPrimvar(UsdGeomTokens->constant).Set(VtFloatArray{0.5f});
    return stage;
}

void placeCamera(UsdStageRefPtr const& stage, GfVec3d const& position) {
    UsdGeomXformable camera(stage->GetPrimAtPath(SdfPath("/Camera")));
    bool resetsXformStack = false;
    camera.GetOrderedXformOps(&resetsXformStack)[0].Set(position);
}

struct Images {
    std::vector<float> color;  // RGBA, from half floats
    std::vector<float> depth;
    std::vector<int> primIds;
};

// A host of the plugin, as usdview is: renders `size` pixels through the
// stage's /Camera with the interactiveBudgetMs setting given.
class Host {
public:
    Host(UsdStageRefPtr stage, int budgetMs, GfVec2i size) : _stage(stage), _engine(cpuEngineParameters()) {
        EXPECT_TRUE(_engine.SetRendererPlugin(kPluginId));
        _engine.SetRendererSetting(TfToken("interactiveBudgetMs"), VtValue(budgetMs));
        _engine.SetCameraPath(SdfPath("/Camera"));
        _engine.SetRenderBufferSize(size);
        _engine.SetFraming(CameraUtilFraming(GfRect2i(GfVec2i(0, 0), size[0], size[1])));
        _params.clearColor = GfVec4f(0.0f);
    }

    // One Render, as one tick of a host's timer; whether it is converged.
    bool step() {
        _engine.Render(_stage->GetPseudoRoot(), _params);
        return _engine.IsConverged();
    }

    // Renders until converged, pausing between renders as usdview does.
    // `readIds`: read the primId AOV too, as a picking host does (the plugin
    // renders ids only once a host reads them).
    Images renderUntilConverged(bool readIds = true) {
        while (!step()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        return read(readIds);
    }

    Images read(bool readIds = true) {
        Images images;
        HdRenderBuffer* color = buffer(HdAovTokens->color);
        GfHalf const* pixels = static_cast<GfHalf const*>(color->Map());
        for (size_t i = 0; i < size_t(color->GetWidth()) * color->GetHeight() * 4; ++i)
            images.color.push_back(float(pixels[i]));
        color->Unmap();
        HdRenderBuffer* depth = buffer(HdAovTokens->depth);
        float const* depths = static_cast<float const*>(depth->Map());
        images.depth.assign(depths, depths + size_t(depth->GetWidth()) * depth->GetHeight());
        depth->Unmap();
        if (!readIds) return images;
        HdRenderBuffer* primId = buffer(HdAovTokens->primId);
        int const* ids = static_cast<int const*>(primId->Map());
        images.primIds.assign(ids, ids + size_t(primId->GetWidth()) * primId->GetHeight());
        primId->Unmap();
        return images;
    }

    HdRenderBuffer* buffer(TfToken const& aov) { return _engine.GetAovRenderBuffer(aov); }

    VtValue stat(char const* name) {
        VtDictionary stats = _engine.GetRenderStats();
        auto found = stats.find(name);
        return found == stats.end() ? VtValue() : found->second;
    }
    int count(char const* name) { return stat(name).GetWithDefault<int>(-1); }

private:
    UsdStageRefPtr _stage;
    UsdImagingGLEngine _engine;
    UsdImagingGLRenderParams _params;
};

// The share of pixels with any alpha.
double coverage(Images const& images) {
    size_t covered = 0;
    for (size_t i = 3; i < images.color.size(); i += 4) covered += images.color[i] > 0.0f ? 1 : 0;
    return double(covered) / double(images.color.size() / 4);
}

void expectIdentical(Images const& actual, Images const& expected) {
    EXPECT_EQ(actual.color, expected.color);
    EXPECT_EQ(actual.depth, expected.depth);
    EXPECT_EQ(actual.primIds, expected.primIds);
}

}  // namespace

TEST_F(HydraProgressiveRendering, ANewViewConvergesOnlyWithItsFullFrameWhichFollowsItsPreview) {
    UsdStageRefPtr stage = wavyFieldStage(300);
    GfVec2i const size(160, 120);
    GfVec3d const first(0, 0, 10), second(0.2, 0.1, 10);  // a small move
    // A host without previews sees the same two views.
    Images expected;
    {
        Host withoutPreviews(stage, 0, size);
        withoutPreviews.renderUntilConverged();
        placeCamera(stage, second);
        expected = withoutPreviews.renderUntilConverged();
        EXPECT_EQ(withoutPreviews.count("hdHairPreviews"), 0);
    }
    EXPECT_GT(coverage(expected), 0.2);

    placeCamera(stage, first);
    // Every full frame takes longer than 1 ms, so once one is in, every new
    // view gets a preview first.
    Host host(stage, 1, size);
    EXPECT_FALSE(host.step());  // the first view asked for: nothing is in yet
    host.renderUntilConverged();
    EXPECT_EQ(host.count("hdHairPreviews"), 0);  // how long frames take is not known before the first
    EXPECT_EQ(host.stat("hdHairShownFrame"), VtValue(std::string("final")));

    placeCamera(stage, second);
    // Asking for the new view makes the pass and its buffers unconverged,
    // however soon its frames finish: they go into the buffers at a later
    // Render only.
    EXPECT_FALSE(host.step());
    EXPECT_FALSE(host.buffer(HdAovTokens->color)->IsConverged());
    EXPECT_FALSE(host.buffer(HdAovTokens->depth)->IsConverged());
    Images const final = host.renderUntilConverged();
    EXPECT_TRUE(host.buffer(HdAovTokens->color)->IsConverged());
    EXPECT_EQ(host.count("hdHairPreviews"), 1);
    EXPECT_EQ(host.count("hdHairFullFrames"), 2);
    EXPECT_EQ(host.count("hdHairCancelledFrames"), 0);
    EXPECT_EQ(host.stat("hdHairShownFrame"), VtValue(std::string("final")));
    expectIdentical(final, expected);

    // Converged stays converged, and nothing more is rendered.
    EXPECT_TRUE(host.step());
    EXPECT_EQ(host.count("hdHairFullFrames"), 2);
    EXPECT_EQ(host.count("hdHairPreviews"), 1);
}

// Ids read only after a new view's preview and full frame are in (a host
// that picks once the view has settled) are the full frame's, as a host
// without previews renders them.
TEST_F(HydraProgressiveRendering, IdsReadAfterAPreviewAreThoseOfTheFullFrame) {
    UsdStageRefPtr stage = wavyFieldStage(300);
    GfVec2i const size(160, 120);
    GfVec3d const first(0, 0, 10), second(0.2, 0.1, 10);
    // The same two views, as the test above renders them.
    Images expected;
    {
        Host withoutPreviews(stage, 0, size);
        withoutPreviews.renderUntilConverged();
        placeCamera(stage, second);
        expected = withoutPreviews.renderUntilConverged();
    }
    placeCamera(stage, first);
    Host host(stage, 1, size);
    host.renderUntilConverged(/*readIds=*/false);
    placeCamera(stage, second);
    host.renderUntilConverged(/*readIds=*/false);
    EXPECT_EQ(host.count("hdHairPreviews"), 1);
    expectIdentical(host.read(), expected);
}

TEST_F(HydraProgressiveRendering, ACameraMoveStopsTheFullFrameInFlightAndEndsOnTheNewView) {
    // Dense enough that a full frame takes a good part of a second or more
    // on llvmpipe; previews off: this is about stopping full frames.
    UsdStageRefPtr stage = wavyFieldStage(4000);
    GfVec2i const size(320, 240);
    GfVec3d const moved(0.0, 0.0, 14.0);  // farther: the first view's image would not pass for it
    Images expected;
    {
        placeCamera(stage, moved);
        Host fresh(stage, 0, size);
        expected = fresh.renderUntilConverged();
    }
    EXPECT_GT(coverage(expected), 0.2);

    placeCamera(stage, GfVec3d(0, 0, 10));
    Host host(stage, 0, size);
    EXPECT_FALSE(host.step());
    // Until the plugin's thread is inside the first view's full frame.
    while (!host.stat("hdHairRendering").GetWithDefault<bool>(false)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        EXPECT_FALSE(host.step());
    }
    placeCamera(stage, moved);
    EXPECT_FALSE(host.step());  // asks for the new view: the frame in flight stops
    Images const final = host.renderUntilConverged();
    EXPECT_EQ(host.count("hdHairCancelledFrames"), 1);
    EXPECT_EQ(host.count("hdHairFullFrames"), 1);  // the new view's only
    EXPECT_EQ(host.stat("hdHairShownFrame"), VtValue(std::string("final")));
    expectIdentical(final, expected);
}
