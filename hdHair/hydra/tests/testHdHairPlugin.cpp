// The Hydra plugin inside OpenUSD (built and run only with OpenUSD): it loads
// through the plugin registry, renders through UsdImagingGL as usdrecord
// does, re-syncs only what an edit touches, and syncs many prims in parallel.
// Run the whole binary under ThreadSanitizer with the build described in
// README ("Hydra plugin", tests).

#include <cmath>
#include <set>
#include <string>
#include <vector>

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
#include "pxr/usd/usdGeom/pointInstancer.h"
#include "pxr/usd/usdGeom/xformable.h"
#include "pxr/usd/usdLux/distantLight.h"
#include "pxr/usd/usdShade/material.h"
#include "pxr/usd/usdShade/materialBindingAPI.h"
#include "pxr/usd/usdShade/shader.h"
#include "pxr/usdImaging/usdImagingGL/engine.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace {

TfToken const kPluginId("HdHairRendererPlugin");

class HdHairPlugin : public ::testing::Test {
protected:
    static void SetUpTestSuite() { PlugRegistry::GetInstance().RegisterPlugins(HDHAIR_PLUGIN_RESOURCES); }
};

// A camera at z = 10 looking down -Z (it sees x in about [-2.1, 2.1]) and a
// light, nothing else.
UsdStageRefPtr cameraAndLightStage() {
    UsdStageRefPtr stage = UsdStage::CreateInMemory();
    UsdGeomCamera camera = UsdGeomCamera::Define(stage, SdfPath("/Camera"));
    camera.AddTranslateOp().Set(GfVec3d(0, 0, 10));
    // UsdLux's DistantLight intensity falls back to 50000 (the Sun): author 1.
    UsdLuxDistantLight::Define(stage, SdfPath("/Light")).CreateIntensityAttr(VtValue(1.0f));
    return stage;
}

// One linear strand from `from` to `to` of constant width.
UsdGeomBasisCurves defineStrand(UsdStageRefPtr const& stage, std::string const& path, GfVec3f from, GfVec3f to,
                                float width) {
    UsdGeomBasisCurves curves = UsdGeomBasisCurves::Define(stage, SdfPath(path));
    curves.CreateTypeAttr(VtValue(UsdGeomTokens->linear));
    curves.CreateCurveVertexCountsAttr(VtValue(VtIntArray{2}));
    curves.CreatePointsAttr(VtValue(VtVec3fArray{from, to}));
    curves.CreateWidthsAttr(VtValue(VtFloatArray{width}));
    return curves;
}

// A PointInstancer placing instance i of prototypes[protoIndices[i]] at positions[i].
UsdGeomPointInstancer defineInstancer(UsdStageRefPtr const& stage, std::string const& path,
                                      std::vector<SdfPath> const& prototypes, VtIntArray const& protoIndices,
                                      VtVec3fArray const& positions) {
    UsdGeomPointInstancer instancer = UsdGeomPointInstancer::Define(stage, SdfPath(path));
    for (SdfPath const& prototype : prototypes) instancer.CreatePrototypesRel().AddTarget(prototype);
    instancer.CreateProtoIndicesAttr(VtValue(protoIndices));
    instancer.CreatePositionsAttr(VtValue(positions));
    return instancer;
}

// Two BasisCurves prims side by side, /A and /B, with the camera and light.
UsdStageRefPtr twoStrandsStage() {
    UsdStageRefPtr stage = cameraAndLightStage();
    defineStrand(stage, "/A", GfVec3f(-1, -1, 0), GfVec3f(-1, 1, 0), 0.2f);
    defineStrand(stage, "/B", GfVec3f(1, -1, 0), GfVec3f(1, 1, 0), 0.2f);
    return stage;
}

struct Frame {
    int width = 0;
    std::vector<float> color;  // RGBA, bottom row first
    std::vector<int> primIds, instanceIds;
    VtDictionary syncCounts;

    float alpha(int x, int y) const { return color[4 * size_t(y * width + x) + 3]; }
    int instanceId(int x, int y) const { return instanceIds[size_t(y * width + x)]; }
};

// The Int32 ids a picking host reads (hosts render them beside color).
std::vector<int> readIds(HdRenderBuffer* buffer) {
    std::vector<int> ids;
    if (!buffer) return ids;
    buffer->Resolve();
    EXPECT_EQ(buffer->GetFormat(), HdFormatInt32);
    const int32_t* values = static_cast<const int32_t*>(buffer->Map());
    ids.assign(values, values + size_t(buffer->GetWidth()) * buffer->GetHeight());
    buffer->Unmap();
    return ids;
}

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
        frame.width = int(color->GetWidth());
        color->Resolve();
        EXPECT_EQ(color->GetFormat(), HdFormatFloat16Vec4);
        const GfHalf* pixels = static_cast<const GfHalf*>(color->Map());
        for (size_t i = 0; i < size_t(color->GetWidth()) * color->GetHeight() * 4; ++i)
            frame.color.push_back(float(pixels[i]));
        color->Unmap();
        frame.primIds = readIds(_engine.GetAovRenderBuffer(HdAovTokens->primId));
        frame.instanceIds = readIds(_engine.GetAovRenderBuffer(HdAovTokens->instanceId));
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

TEST_F(HdHairPlugin, AMaterialEditRecoloursBoundCurvesWithoutResyncingThem) {
    UsdStageRefPtr stage = twoStrandsStage();
    UsdShadeMaterial material = UsdShadeMaterial::Define(stage, SdfPath("/Looks/hair"));
    UsdShadeShader surface = UsdShadeShader::Define(stage, SdfPath("/Looks/hair/Surface"));
    surface.CreateIdAttr(VtValue(TfToken("UsdPreviewSurface")));
    UsdShadeInput diffuse = surface.CreateInput(TfToken("diffuseColor"), SdfValueTypeNames->Color3f);
    diffuse.Set(GfVec3f(1.0f, 0.0f, 0.0f));
    material.CreateSurfaceOutput().ConnectToSource(surface.ConnectableAPI(), TfToken("surface"));
    for (char const* path : {"/A", "/B"})
        UsdShadeMaterialBindingAPI::Apply(stage->GetPrimAtPath(SdfPath(path))).Bind(material);

    // The mean colour of covered pixels (un-premultiplied).
    auto meanColor = [](Frame const& frame) {
        GfVec3d sum(0.0);
        double alpha = 0.0;
        for (size_t i = 0; i < frame.color.size(); i += 4) {
            sum += GfVec3d(frame.color[i], frame.color[i + 1], frame.color[i + 2]);
            alpha += frame.color[i + 3];
        }
        return alpha > 0.0 ? sum / alpha : sum;
    };
    Recorder recorder(stage);
    Frame red = recorder.render();
    GfVec3d redMean = meanColor(red);
    // Kajiya-Kay's white specular highlight dilutes the hue: 2.5x margins.
    EXPECT_GT(redMean[0], 2.5 * redMean[1]) << redMean;
    EXPECT_GT(redMean[0], 2.5 * redMean[2]) << redMean;

    diffuse.Set(GfVec3f(0.0f, 0.0f, 1.0f));
    Frame blue = recorder.render();
    GfVec3d blueMean = meanColor(blue);
    EXPECT_GT(blueMean[2], 2.5 * blueMean[0]) << blueMean;
    EXPECT_GT(blueMean[2], 2.5 * blueMean[1]) << blueMean;
    EXPECT_EQ(syncs(blue, "/A"), syncs(red, "/A")) << "the curves were re-synced";
    EXPECT_GT(syncs(blue, "/Looks/hair"), syncs(red, "/Looks/hair"));
}

TEST_F(HdHairPlugin, PointInstancerInstancesAreDrawnScaledAndPickable) {
    UsdStageRefPtr stage = cameraAndLightStage();
    // The prototype sits at the origin, where nothing may be drawn: only its
    // instances are.
    UsdGeomBasisCurves strand =
        defineStrand(stage, "/Instancer/Prototypes/strand", GfVec3f(0, -0.5f, 0), GfVec3f(0, 0.5f, 0), 0.1f);
    UsdGeomPointInstancer instancer = defineInstancer(stage, "/Instancer", {strand.GetPath()}, {0, 0},
                                                      {GfVec3f(-1.2f, 0, 0), GfVec3f(1.2f, 0, 0)});
    // The second instance is twice as big (widths too) and turned upside down
    // (a quath orientation, as PointInstancers author them).
    instancer.CreateScalesAttr(VtValue(VtVec3fArray{GfVec3f(1.0f), GfVec3f(2.0f)}));
    instancer.CreateOrientationsAttr(VtValue(VtQuathArray{GfQuath(1.0f), GfQuath(0.0f, GfVec3h(0, 0, 1))}));

    Recorder recorder(stage);
    Frame frame = recorder.render();
    ASSERT_EQ(frame.instanceIds.size(), frame.color.size() / 4);
    const int height = int(frame.instanceIds.size()) / frame.width;
    // Coverage (summed alpha) per half, and the instance ids there.
    double left = 0.0, right = 0.0, middle = 0.0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            float alpha = frame.alpha(x, y);
            if (alpha <= 0.0f) continue;
            EXPECT_EQ(frame.instanceId(x, y), x < frame.width / 2 ? 0 : 1) << "pixel " << x << "," << y;
            EXPECT_GE(frame.primIds[size_t(y * frame.width + x)], 0) << "pixel " << x << "," << y;
            if (std::abs(x - frame.width / 2) <= 2) middle += alpha;
            (x < frame.width / 2 ? left : right) += alpha;
        }
    }
    EXPECT_EQ(middle, 0.0) << "the prototype itself was drawn";
    ASSERT_GT(left, 1.0);
    // Scaled 2x: twice as long and, because the scale reaches the widths,
    // twice as wide on screen: four times the coverage.
    EXPECT_NEAR(right / left, 4.0, 1.0);

    // Moving the instances re-syncs the prototype and moves the picture.
    instancer.GetPositionsAttr().Set(VtVec3fArray{GfVec3f(-0.6f, 0, 0), GfVec3f(0.6f, 0, 0)});
    Frame moved = recorder.render();
    EXPECT_NE(moved.color, frame.color);
    // UsdImaging names the prototype rprim after the instancer and prototype.
    std::string prototype;
    for (auto const& entry : frame.syncCounts)
        if (entry.first.rfind("/Instancer/", 0) == 0) prototype = entry.first;
    ASSERT_FALSE(prototype.empty());
    EXPECT_GT(syncs(moved, prototype), syncs(frame, prototype)) << prototype;

    // Without scales both instances are the same size again.
    auto halves = [](Frame const& f) {
        double sums[2] = {0.0, 0.0};
        for (size_t i = 0; i < f.color.size() / 4; ++i) sums[int(i % size_t(f.width)) >= f.width / 2] += f.color[4 * i + 3];
        return std::make_pair(sums[0], sums[1]);
    };
    instancer.GetScalesAttr().Block();
    auto [unscaledLeft, unscaledRight] = halves(recorder.render());
    EXPECT_NEAR(unscaledRight / unscaledLeft, 1.0, 0.2);
}

TEST_F(HdHairPlugin, NestedInstancersComposeTheirTransforms) {
    // An outer PointInstancer places two copies of an inner one, which places
    // two strands: four strands, one in each quadrant, instance ids 0 to 3.
    UsdStageRefPtr stage = cameraAndLightStage();
    UsdGeomBasisCurves strand = defineStrand(stage, "/Outer/Prototypes/inner/Prototypes/s", GfVec3f(0, -0.4f, 0),
                                             GfVec3f(0, 0.4f, 0), 0.15f);
    UsdGeomPointInstancer inner = defineInstancer(stage, "/Outer/Prototypes/inner", {strand.GetPath()}, {0, 0},
                                                  {GfVec3f(-1.0f, 0, 0), GfVec3f(1.0f, 0, 0)});
    defineInstancer(stage, "/Outer", {inner.GetPath()}, {0, 0}, {GfVec3f(0, -0.8f, 0), GfVec3f(0, 0.8f, 0)});

    Recorder recorder(stage);
    Frame frame = recorder.render();
    const int height = int(frame.instanceIds.size()) / frame.width;
    double quadrant[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    std::set<int> ids;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < frame.width; ++x)
            if (frame.alpha(x, y) > 0.0f) {
                quadrant[y < height / 2][x < frame.width / 2] += frame.alpha(x, y);
                ids.insert(frame.instanceId(x, y));
            }
    for (auto const& row : quadrant)
        for (double covered : row) EXPECT_GT(covered, 1.0);
    EXPECT_EQ(ids, (std::set<int>{0, 1, 2, 3}));
}

TEST_F(HdHairPlugin, PrototypesSharingAnInstancerSyncInParallel) {
    // 64 prototypes of one PointInstancer sync on Hydra's worker threads,
    // each syncing the shared instancer first (under its lock) and then
    // reading its transforms: run under ThreadSanitizer (README).
    UsdStageRefPtr stage = cameraAndLightStage();
    constexpr int kPrototypes = 64, kInstances = 2048;
    std::vector<SdfPath> prototypes;
    for (int p = 0; p < kPrototypes; ++p)
        prototypes.push_back(defineStrand(stage, "/Instancer/Prototypes/p" + std::to_string(p), GfVec3f(0.0f),
                                          GfVec3f(0.01f * float(p), 0.05f, 0.0f), 0.01f)
                                 .GetPath());
    VtIntArray protoIndices(kInstances);
    VtVec3fArray positions(kInstances);
    for (int i = 0; i < kInstances; ++i) {
        protoIndices[i] = i % kPrototypes;
        positions[i] = GfVec3f(-1.8f + 3.6f * float(i % 64) / 63.0f, -1.4f + 2.8f * float(i / 64) / 31.0f, 0.0f);
    }
    defineInstancer(stage, "/Instancer", prototypes, protoIndices, positions);
    Recorder recorder(stage);
    Frame frame = recorder.render();
    int synced = 0;
    for (auto const& entry : frame.syncCounts) synced += entry.first.rfind("/Instancer/", 0) == 0 ? 1 : 0;
    EXPECT_EQ(synced, kPrototypes);
    std::set<int> instanceIds(frame.instanceIds.begin(), frame.instanceIds.end());
    // Each prototype has 32 instances (ids 0 to 31) and empty pixels are -1.
    EXPECT_EQ(*instanceIds.begin(), -1);
    EXPECT_EQ(*instanceIds.rbegin(), kInstances / kPrototypes - 1);
    EXPECT_GT(coverage(frame), 0.05);
}

TEST_F(HdHairPlugin, TenThousandCurvesSyncInParallel) {
    UsdStageRefPtr stage = twoStrandsStage();
    for (int i = 0; i < 10000; ++i) {
        float x = -4.0f + 8.0f * float(i % 100) / 99.0f, y = -3.0f + 6.0f * float(i / 100) / 99.0f;
        defineStrand(stage, "/Many/c" + std::to_string(i), GfVec3f(x, y, 0), GfVec3f(x + 0.05f, y + 0.05f, 0), 0.02f);
    }
    Recorder recorder(stage);
    Frame frame = recorder.render();
    int synced = 0;
    for (auto const& [path, count] : frame.syncCounts) synced += path.rfind("/Many/", 0) == 0 ? 1 : 0;
    EXPECT_EQ(synced, 10000);
    EXPECT_GT(coverage(frame), 0.01);
}
