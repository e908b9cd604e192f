// The Hydra plugin inside OpenUSD (built and run only with OpenUSD): it loads
// through the plugin registry, renders through UsdImagingGL as usdrecord
// does, re-syncs only what an edit touches, and syncs many prims in parallel.
// Run the whole binary under ThreadSanitizer with the build described in
// README ("Hydra plugin", tests).

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "pxr/base/gf/rect2i.h"
#include "pxr/base/plug/registry.h"
#include "pxr/base/vt/dictionary.h"
#include "pxr/imaging/cameraUtil/framing.h"
#include "pxr/imaging/hd/renderBuffer.h"
#include "pxr/imaging/hd/rendererPlugin.h"
#include "pxr/imaging/hd/rendererPluginHandle.h"
#include "pxr/imaging/hd/rendererPluginRegistry.h"
#include "pxr/imaging/hd/tokens.h"
#include "pxr/imaging/hf/pluginDesc.h"
#include "pxr/usd/sdf/layer.h"
#include "pxr/usd/usd/stage.h"
#include "pxr/usd/usdGeom/basisCurves.h"
#include "pxr/usd/usdGeom/camera.h"
#include "pxr/usd/usdGeom/xformable.h"
#include "pxr/usd/usdLux/distantLight.h"
#include "pxr/usdImaging/usdImagingGL/engine.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace {

TfToken const kPluginId("HdHairRendererPlugin");

class HdHairPlugin : public ::testing::Test {
protected:
    static void SetUpTestSuite() { PlugRegistry::GetInstance().RegisterPlugins(HDHAIR_PLUGIN_RESOURCES); }
};

// Two BasisCurves prims side by side, a camera looking at them and a light.
UsdStageRefPtr twoStrandsStage() {
    UsdStageRefPtr stage = UsdStage::CreateInMemory();
    for (int i = 0; i < 2; ++i) {
        UsdGeomBasisCurves curves = UsdGeomBasisCurves::Define(stage, SdfPath(i == 0 ? "/A" : "/B"));
        curves.CreateTypeAttr(VtValue(UsdGeomTokens->linear));
        curves.CreateCurveVertexCountsAttr(VtValue(VtIntArray{2}));
        float x = i == 0 ? -1.0f : 1.0f;
        curves.CreatePointsAttr(VtValue(VtVec3fArray{GfVec3f(x, -1, 0), GfVec3f(x, 1, 0)}));
        curves.CreateWidthsAttr(VtValue(VtFloatArray{0.2f}));
    }
    UsdGeomCamera camera = UsdGeomCamera::Define(stage, SdfPath("/Camera"));
    camera.AddTranslateOp().Set(GfVec3d(0, 0, 10));
    // UsdLux's DistantLight intensity falls back to 50000 (the Sun): author 1.
    UsdLuxDistantLight::Define(stage, SdfPath("/Light")).CreateIntensityAttr(VtValue(1.0f));
    return stage;
}

struct Frame {
    std::vector<float> color;  // RGBA, bottom row first
    VtDictionary syncCounts;
};

class Recorder {
public:
    explicit Recorder(UsdStageRefPtr stage) : _stage(stage), _engine(parameters()) {
        EXPECT_TRUE(_engine.SetRendererPlugin(kPluginId));
        _engine.SetCameraPath(SdfPath("/Camera"));
        _engine.SetRenderBufferSize(GfVec2i(64, 48));
        _engine.SetFraming(CameraUtilFraming(GfRect2i(GfVec2i(0, 0), 64, 48)));
    }

    Frame render(double time = 0.0) {
        UsdImagingGLRenderParams params;
        params.frame = UsdTimeCode(time);
        params.clearColor = GfVec4f(0.0f);
        do {
            _engine.Render(_stage->GetPseudoRoot(), params);
        } while (!_engine.IsConverged());
        Frame frame;
        HdRenderBuffer* color = _engine.GetAovRenderBuffer(HdAovTokens->color);
        color->Resolve();
        EXPECT_EQ(color->GetFormat(), HdFormatFloat16Vec4);
        const GfHalf* pixels = static_cast<const GfHalf*>(color->Map());
        for (size_t i = 0; i < size_t(color->GetWidth()) * color->GetHeight() * 4; ++i)
            frame.color.push_back(float(pixels[i]));
        color->Unmap();
        VtDictionary stats = _engine.GetRenderStats();
        if (stats.count("hdHairSyncCounts")) frame.syncCounts = stats["hdHairSyncCounts"].Get<VtDictionary>();
        return frame;
    }

private:
    static UsdImagingGLEngine::Parameters parameters() {
        UsdImagingGLEngine::Parameters p;
        p.gpuEnabled = false;
        return p;
    }
    UsdStageRefPtr _stage;
    UsdImagingGLEngine _engine;
};

int syncs(Frame const& frame, std::string const& path) {
    auto it = frame.syncCounts.find(path);
    return it == frame.syncCounts.end() ? 0 : it->second.Get<int>();
}

double coverage(Frame const& frame) {
    size_t covered = 0;
    for (size_t i = 3; i < frame.color.size(); i += 4) covered += frame.color[i] > 0.0f ? 1 : 0;
    return double(covered) / double(frame.color.size() / 4);
}

}  // namespace

TEST_F(HdHairPlugin, LoadsThroughTheRegistryWithoutBecomingTheDefault) {
    HfPluginDesc desc;
    ASSERT_TRUE(HdRendererPluginRegistry::GetInstance().GetPluginDesc(kPluginId, &desc));
    EXPECT_EQ(desc.displayName, "HdHair");
    EXPECT_GE(desc.priority, 100);
    // Storm stays the default wherever it can run (it needs the host's GL,
    // which this test does not create, so compare priorities).
    HfPluginDesc storm;
    if (HdRendererPluginRegistry::GetInstance().GetPluginDesc(TfToken("HdStormRendererPlugin"), &storm)) {
        EXPECT_GT(desc.priority, storm.priority);
    }
    // The handle releases the plugin when it goes out of scope.
    HdRendererPluginHandle plugin = HdRendererPluginRegistry::GetInstance().GetOrCreateRendererPlugin(kPluginId);
    ASSERT_TRUE(plugin);
    EXPECT_TRUE(plugin->IsSupported(false));
    HdRenderDelegate* delegate = plugin->CreateRenderDelegate();
    ASSERT_NE(delegate, nullptr);
    auto supports = [](TfTokenVector const& types, TfToken const& type) {
        return std::find(types.begin(), types.end(), type) != types.end();
    };
    EXPECT_TRUE(supports(delegate->GetSupportedRprimTypes(), HdPrimTypeTokens->basisCurves));
    EXPECT_TRUE(supports(delegate->GetSupportedSprimTypes(), HdPrimTypeTokens->simpleLight));
    EXPECT_TRUE(supports(delegate->GetSupportedBprimTypes(), HdPrimTypeTokens->renderBuffer));
    EXPECT_EQ(delegate->GetDefaultAovDescriptor(HdAovTokens->color).format, HdFormatFloat16Vec4);
    EXPECT_EQ(delegate->GetDefaultAovDescriptor(HdAovTokens->primId).format, HdFormatInt32);
    // Every engine setting is a Hydra render setting.
    bool found = false;
    for (HdRenderSettingDescriptor const& d : delegate->GetRenderSettingDescriptors())
        found = found || d.key == TfToken("maxSegmentsPerSpan");
    EXPECT_TRUE(found);
    plugin->DeleteRenderDelegate(delegate);
}

TEST_F(HdHairPlugin, EditsResyncOnlyTheTouchedPrimAndChangeTheImage) {
    UsdStageRefPtr stage = twoStrandsStage();
    Recorder recorder(stage);
    Frame first = recorder.render();
    ASSERT_GT(coverage(first), 0.01);
    int a = syncs(first, "/A"), b = syncs(first, "/B");
    ASSERT_GE(a, 1);

    auto expectOnlyA = [&](Frame const& frame, char const* edit) {
        EXPECT_EQ(syncs(frame, "/B"), b) << edit << " touched /B";
        EXPECT_GT(syncs(frame, "/A"), a) << edit << " did not re-sync /A";
        a = syncs(frame, "/A");
    };
    UsdGeomBasisCurves curvesA(stage->GetPrimAtPath(SdfPath("/A")));

    // The camera sees x in about [-2.1, 2.1]: stay in view.
    curvesA.GetPointsAttr().Set(VtVec3fArray{GfVec3f(-1.5f, -1, 0), GfVec3f(-1.5f, 1, 0)});
    Frame moved = recorder.render();
    expectOnlyA(moved, "points");
    EXPECT_NE(moved.color, first.color);

    curvesA.GetWidthsAttr().Set(VtFloatArray{0.6f});
    Frame wider = recorder.render();
    expectOnlyA(wider, "widths");
    EXPECT_GT(coverage(wider), coverage(moved));

    UsdGeomXformable(curvesA).AddTranslateOp().Set(GfVec3d(0, 0.5, 0));
    Frame translated = recorder.render();
    expectOnlyA(translated, "transform");
    EXPECT_NE(translated.color, wider.color);

    curvesA.MakeInvisible();
    Frame hidden = recorder.render();
    expectOnlyA(hidden, "visibility");
    EXPECT_LT(coverage(hidden), coverage(translated));
}

TEST_F(HdHairPlugin, TenThousandCurvesSyncInParallel) {
    UsdStageRefPtr stage = twoStrandsStage();
    for (int i = 0; i < 10000; ++i) {
        UsdGeomBasisCurves curves =
            UsdGeomBasisCurves::Define(stage, SdfPath("/Many/c" + std::to_string(i)));
        curves.CreateTypeAttr(VtValue(UsdGeomTokens->linear));
        curves.CreateCurveVertexCountsAttr(VtValue(VtIntArray{2}));
        float x = -4.0f + 8.0f * float(i % 100) / 99.0f, y = -3.0f + 6.0f * float(i / 100) / 99.0f;
        curves.CreatePointsAttr(VtValue(VtVec3fArray{GfVec3f(x, y, 0), GfVec3f(x + 0.05f, y + 0.05f, 0)}));
        curves.CreateWidthsAttr(VtValue(VtFloatArray{0.02f}));
    }
    Recorder recorder(stage);
    Frame frame = recorder.render();
    int synced = 0;
    for (auto const& [path, count] : frame.syncCounts) synced += path.rfind("/Many/", 0) == 0 ? 1 : 0;
    EXPECT_EQ(synced, 10000);
    EXPECT_GT(coverage(frame), 0.01);
}
