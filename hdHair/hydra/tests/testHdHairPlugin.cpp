// The Hydra plugin inside OpenUSD (built and run only with OpenUSD): it loads
// through the plugin registry, renders through UsdImagingGL as usdrecord
// does, fills every AOV with the values a host expects, re-syncs only what an
// edit touches, and syncs many prims in parallel.
// Run the whole binary under ThreadSanitizer with the build described in
// docs/hydra-plugin.md (tests).

#include <link.h>

#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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
#include "pxr/usd/usdGeom/mesh.h"
#include "pxr/usd/usdGeom/pointInstancer.h"
#include "pxr/usd/usdGeom/xformable.h"
#include "pxr/usd/usdLux/distantLight.h"
#include "pxr/usd/usdLux/domeLight.h"
#include "pxr/usd/usdShade/material.h"
#include "pxr/usd/usdShade/materialBindingAPI.h"
#include "pxr/usd/usdShade/shader.h"
#include "pxr/usdImaging/usdImagingGL/engine.h"

#include "CpuEngineParameters.h"

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
    std::vector<float> depth;  // bottom row first, like every AOV below
    std::vector<int> primIds, instanceIds, elementIds;
    VtDictionary syncCounts;
    std::string frameStats;  // the plugin's last full frame (RenderStats.h), JSON
    std::string plan;        // and its plan (FrameGraph::describe)

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

// The Float32 depth a host reads (window depth, 1 where empty).
std::vector<float> readDepth(HdRenderBuffer* buffer) {
    std::vector<float> depth;
    if (!buffer) return depth;
    buffer->Resolve();
    EXPECT_EQ(buffer->GetFormat(), HdFormatFloat32);
    const float* values = static_cast<const float*>(buffer->Map());
    depth.assign(values, values + size_t(buffer->GetWidth()) * buffer->GetHeight());
    buffer->Unmap();
    return depth;
}

class Recorder {
public:
    explicit Recorder(UsdStageRefPtr stage) : _stage(stage), _engine(cpuEngineParameters()) {
        EXPECT_TRUE(_engine.SetRendererPlugin(kPluginId));
        _engine.SetCameraPath(SdfPath("/Camera"));
        _engine.SetRenderBufferSize(GfVec2i(64, 48));
        _engine.SetFraming(CameraUtilFraming(GfRect2i(GfVec2i(0, 0), 64, 48)));
    }

    // usdview's complexity (1.0 low to 1.3 veryhigh): Storm's refine levels 0 to 3.
    void setComplexity(float complexity) { _complexity = complexity; }

    // `readIds`: read the id AOVs too, as a picking host does (the plugin
    // renders them only once a host reads them).
    Frame render(double time = 0.0, bool readIds = true) {
        UsdImagingGLRenderParams params;
        params.frame = UsdTimeCode(time);
        params.complexity = _complexity;
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
        frame.depth = readDepth(_engine.GetAovRenderBuffer(HdAovTokens->depth));
        if (readIds) readAllIds(frame);
        VtDictionary stats = _engine.GetRenderStats();
        if (stats.count("hdHairSyncCounts")) frame.syncCounts = stats["hdHairSyncCounts"].Get<VtDictionary>();
        if (stats.count("hdHairFrameStats")) frame.frameStats = stats["hdHairFrameStats"].Get<std::string>();
        if (stats.count("hdHairPlan")) frame.plan = stats["hdHairPlan"].Get<std::string>();
        return frame;
    }

    // The id AOVs of the frame the buffers hold, read now.
    void readAllIds(Frame& frame) {
        frame.primIds = readIds(_engine.GetAovRenderBuffer(HdAovTokens->primId));
        frame.instanceIds = readIds(_engine.GetAovRenderBuffer(HdAovTokens->instanceId));
        frame.elementIds = readIds(_engine.GetAovRenderBuffer(HdAovTokens->elementId));
    }

    // A render setting, as usdview's Hydra Settings set it.
    void setSetting(std::string const& name, std::string const& value) {
        _engine.SetRendererSetting(TfToken(name), VtValue(value));
    }

    // The prim a primId names, decoded the way a picking host does.
    SdfPath primPath(int primId) {
        unsigned char primColor[4], instanceColor[4] = {0, 0, 0, 0};
        for (int i = 0; i < 4; ++i) primColor[i] = static_cast<unsigned char>((unsigned(primId) >> (8 * i)) & 0xffu);
        SdfPath path;
        return _engine.DecodeIntersection(primColor, instanceColor, &path) ? path : SdfPath();
    }

private:
    UsdStageRefPtr _stage;
    UsdImagingGLEngine _engine;
    float _complexity = 1.0f;
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

// Whether a shared object whose path contains `name` is loaded in this process.
bool sharedObjectLoaded(const char* name) {
    struct Search {
        const char* name;
        bool found;
    } search{name, false};
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void* data) {
            Search* s = static_cast<Search*>(data);
            if (info->dlpi_name && std::strstr(info->dlpi_name, s->name)) s->found = true;
            return 0;
        },
        &search);
    return search.found;
}

// The summed RGB of the frame's pixels.
double totalColor(Frame const& frame) {
    double total = 0.0;
    for (size_t i = 0; i < frame.color.size(); i += 4) total += frame.color[i] + frame.color[i + 1] + frame.color[i + 2];
    return total;
}

}  // namespace

// OpenImageIO and the libraries it pulls in cost a host about 0.36 s and
// 124 MB to load; the plugin loads them (hdHairImageReader.so) only when a
// stage has a dome texture, and then reads the texture through them.
TEST_F(HdHairPlugin, OpenImageIOLoadsOnlyForADomeTexture) {
    ASSERT_FALSE(sharedObjectLoaded("libOpenImageIO")) << "this test's own program loads OpenImageIO";
    UsdStageRefPtr stage = twoStrandsStage();
    Recorder recorder(stage);
    const Frame plain = recorder.render();
    EXPECT_GT(coverage(plain), 0.0);
    EXPECT_FALSE(sharedObjectLoaded("hdHairImageReader"));
    EXPECT_FALSE(sharedObjectLoaded("libOpenImageIO"));
    EXPECT_FALSE(sharedObjectLoaded("libOpenColorIO"));

    UsdLuxDomeLight dome = UsdLuxDomeLight::Define(stage, SdfPath("/Dome"));
    dome.CreateTextureFileAttr(VtValue(SdfAssetPath(HDHAIR_DOME_TEXTURE)));
    dome.CreateIntensityAttr(VtValue(1.0f));
    const Frame domed = recorder.render();
    EXPECT_TRUE(sharedObjectLoaded("hdHairImageReader"));
    EXPECT_TRUE(sharedObjectLoaded("libOpenImageIO"));
    // The texture was read (a texture that cannot be is a warning, and the
    // dome falls back to uniform light), and it lights the strands.
    const nlohmann::json stats = nlohmann::json::parse(domed.frameStats);
    EXPECT_EQ(stats["warnings"].get<int>(), 0);
    EXPECT_GT(totalColor(domed), 1.05 * totalColor(plain));
}

// Whether the frame rendered ids, as its plan says (RenderPlan.cpp's
// idsPass: a pass of their own, or written by the strand pass).
bool renderedIds(Frame const& frame) {
    EXPECT_NE(frame.plan.find("ids"), std::string::npos) << "no plan: " << frame.plan;
    return frame.plan.find("no ids asked for") == std::string::npos;
}

// usdrecord and usdview bind the id AOVs but read them only to pick or to
// highlight a selection: the plugin renders them when a host first reads
// them (DeferredIds.h), with the frame's own view, and with every frame after.
TEST_F(HdHairPlugin, IdsAreRenderedWhenAHostFirstReadsThem) {
    UsdStageRefPtr stage = twoStrandsStage();
    Recorder recorder(stage);
    Frame frame = recorder.render(0.0, /*readIds=*/false);
    EXPECT_FALSE(renderedIds(frame));
    recorder.readAllIds(frame);
    // Every covered pixel of the middle row names the strand over it: /A on
    // the left half, /B on the right; empty pixels name nothing.
    const int row = 24;
    int named = 0;
    for (int x = 0; x < frame.width; ++x) {
        const int id = frame.primIds[size_t(row * frame.width + x)];
        if (frame.alpha(x, row) <= 0.0f) continue;
        EXPECT_EQ(recorder.primPath(id), SdfPath(x < frame.width / 2 ? "/A" : "/B")) << "pixel " << x;
        ++named;
    }
    EXPECT_GT(named, 2);
    int empty = 0;
    for (int id : frame.primIds) empty += id == -1 ? 1 : 0;
    EXPECT_GT(empty, 0);

    // Read once, the ids come with every frame: the next view renders them.
    stage->GetPrimAtPath(SdfPath("/Camera")).GetAttribute(TfToken("xformOp:translate")).Set(GfVec3d(0.1, 0, 10));
    const Frame moved = recorder.render(0.0, /*readIds=*/false);
    EXPECT_TRUE(renderedIds(moved));
}

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

// quality is a Hydra render setting like every other (usdview lists it), its
// preset reaches the engine, and usdview's complexity above low wins over the
// preset's tessellation while low (every host's default) does not.
TEST_F(HdHairPlugin, TheQualityPresetIsARenderSettingAndAComplexityAboveLowWinsOverIt) {
    HdRendererPluginHandle plugin = HdRendererPluginRegistry::GetInstance().GetOrCreateRendererPlugin(kPluginId);
    ASSERT_TRUE(plugin);
    HdRenderDelegate* delegate = plugin->CreateRenderDelegate();
    std::set<std::string> keys;
    for (HdRenderSettingDescriptor const& d : delegate->GetRenderSettingDescriptors()) keys.insert(d.key.GetString());
    EXPECT_EQ(keys.count("quality"), 1u);
    EXPECT_EQ(keys.count("supersampling"), 1u);
    EXPECT_EQ(keys.count("exactOverflow"), 1u);
    plugin->DeleteRenderDelegate(delegate);

    UsdStageRefPtr stage = cameraAndLightStage();
    defineStrand(stage, "/Strand", GfVec3f(-1.5f, 0.0f, 0.0f), GfVec3f(1.5f, 0.2f, 0.0f), 0.05f);
    Recorder recorder(stage);
    recorder.setSetting("quality", "reference");
    const Frame low = recorder.render();
    EXPECT_EQ(low.width, 64);
    const nlohmann::json lowStats = nlohmann::json::parse(low.frameStats);
    EXPECT_EQ(lowStats["settings"]["quality"], "reference");
    EXPECT_EQ(lowStats["settings"]["transparency"], "exact");  // (an opaque, wide strand takes the opaque path)
    EXPECT_EQ(lowStats["supersampling"], 4);
    EXPECT_EQ(lowStats["image"]["width"], 64);
    EXPECT_DOUBLE_EQ(lowStats["settings"]["tessellationTolerance"].get<double>(), 0.001);
    EXPECT_EQ(lowStats["settingOrigins"]["tessellationTolerance"]["source"], "quality=reference");
    EXPECT_GT(coverage(low), 0.0);
    recorder.setComplexity(1.2f);  // high
    const nlohmann::json highStats = nlohmann::json::parse(recorder.render().frameStats);
    EXPECT_DOUBLE_EQ(highStats["settings"]["tessellationTolerance"].get<double>(), 0.03);
    EXPECT_EQ(highStats["settingOrigins"]["tessellationTolerance"]["source"], "complexity high");
    EXPECT_EQ(highStats["settingOrigins"]["tessellationTolerance"]["overriddenPreset"], "0.001");
    EXPECT_EQ(highStats["settingOrigins"]["transparency"]["source"], "quality=reference");
}

TEST_F(HdHairPlugin, EveryAovHoldsTheNearestQualifyingStrandInEveryTransparencyMode) {
    // A 20 x 15 aperture, focal length 50 camera at z = 10, clipping range
    // [n, f] = [1, 21], rendered 64 x 48 (the aperture's aspect): at distance
    // d the image spans 0.4 d units, 160 / d pixels a unit, and window depth
    // is f / (f - n) * (1 - n / d). Flat shading, so colours follow from the
    // over operator.
    UsdStageRefPtr stage = UsdStage::CreateInMemory();
    UsdGeomCamera camera = UsdGeomCamera::Define(stage, SdfPath("/Camera"));
    camera.AddTranslateOp().Set(GfVec3d(0, 0, 10));
    camera.CreateHorizontalApertureAttr(VtValue(20.0f));
    camera.CreateVerticalApertureAttr(VtValue(15.0f));
    camera.CreateFocalLengthAttr(VtValue(50.0f));
    camera.CreateClippingRangeAttr(VtValue(GfVec2f(1.0f, 21.0f)));
    // Strands along x at depth z, one curve per pixel row (from the top)
    // through that row's centre; 0.4 wide: 6 to 11 pixels.
    auto layer = [&](std::string const& path, float z, std::vector<int> const& rows, GfVec3f color, float opacity) {
        VtIntArray counts;
        VtVec3fArray points;
        for (int row : rows) {
            float y = (23.5f - float(row)) * (10.0f - z) / 160.0f;
            counts.push_back(2);
            points.push_back(GfVec3f(-5.0f, y, z));
            points.push_back(GfVec3f(5.0f, y, z));
        }
        UsdGeomBasisCurves curves = UsdGeomBasisCurves::Define(stage, SdfPath(path));
        curves.CreateTypeAttr(VtValue(UsdGeomTokens->linear));
        curves.CreateCurveVertexCountsAttr(VtValue(counts));
        curves.CreatePointsAttr(VtValue(points));
        curves.CreateWidthsAttr(VtValue(VtFloatArray{0.4f}));
        curves.CreateDisplayColorPrimvar(UsdGeomTokens->constant).Set(VtVec3fArray{color});
        curves.CreateDisplayOpacityPrimvar(UsdGeomTokens->constant).Set(VtFloatArray{opacity});
    };
    // Paths in the order unsorted drawing takes them: nearest first.
    layer("/A_front", 2.0f, {12}, GfVec3f(0, 0, 1), 0.5f);          // d = 8
    layer("/B_faint", 4.0f, {24}, GfVec3f(0, 1, 0), 0.05f);         // d = 6: alpha under 0.1
    layer("/C_back", 0.0f, {12, 24, 36}, GfVec3f(1, 0, 0), 1.0f);   // d = 10, elementIds 0, 1, 2
    const float front = 21.0f / 20.0f * (1.0f - 1.0f / 8.0f);       // 0.91875
    const float faint = 21.0f / 20.0f * (1.0f - 1.0f / 6.0f);       // 0.875
    const float back = 21.0f / 20.0f * (1.0f - 1.0f / 10.0f);       // 0.945

    struct Expected {
        int row;
        GfVec4f color;
        float depth;
        char const* prim;  // "" for none: ids -1
        int elementId;
    };
    std::vector<Expected> const sorted = {
        {12, GfVec4f(0.5f, 0.0f, 0.5f, 1.0f), front, "/A_front", 0},   // blue 0.5 over red
        {24, GfVec4f(0.95f, 0.05f, 0.0f, 1.0f), back, "/C_back", 1},   // green 0.05 looked through
        {36, GfVec4f(1.0f, 0.0f, 0.0f, 1.0f), back, "/C_back", 2},
        {44, GfVec4f(0.0f), 1.0f, "", -1},
    };
    std::vector<Expected> unsorted = sorted;  // the opaque red drawn last covers what came first
    unsorted[0].color = unsorted[1].color = GfVec4f(1.0f, 0.0f, 0.0f, 1.0f);
    std::vector<Expected> opaque = sorted;    // opacity ignored: the nearest strand wins
    opaque[0].color = GfVec4f(0.0f, 0.0f, 1.0f, 1.0f);
    opaque[1] = {24, GfVec4f(0.0f, 1.0f, 0.0f, 1.0f), faint, "/B_faint", 0};

    Recorder recorder(stage);
    recorder.setSetting("shadingModel", "flat");
    struct Mode {
        char const* transparency;
        std::vector<Expected> const* expected;
    };
    for (Mode const& mode : {Mode{"binSorted", &sorted}, Mode{"exact", &sorted}, Mode{"unsorted", &unsorted},
                             Mode{"opaque", &opaque}}) {
        recorder.setSetting("transparency", mode.transparency);
        Frame frame = recorder.render();
        const size_t pixels = frame.color.size() / 4;
        ASSERT_EQ(frame.depth.size(), pixels) << mode.transparency;
        ASSERT_EQ(frame.primIds.size(), pixels) << mode.transparency;
        ASSERT_EQ(frame.instanceIds.size(), pixels) << mode.transparency;
        ASSERT_EQ(frame.elementIds.size(), pixels) << mode.transparency;
        const int height = int(pixels) / frame.width;
        for (Expected const& pixel : *mode.expected) {
            // Hydra's buffers run bottom-up.
            const size_t index = size_t((height - 1 - pixel.row) * frame.width + frame.width / 2);
            const std::string where = std::string(mode.transparency) + ", row " + std::to_string(pixel.row);
            for (int c = 0; c < 4; ++c)  // half floats
                EXPECT_NEAR(frame.color[4 * index + size_t(c)], pixel.color[c], 2e-3) << where << ", colour " << c;
            EXPECT_NEAR(frame.depth[index], pixel.depth, 1e-5) << where << ", depth";
            const bool covered = pixel.prim[0] != '\0';
            if (covered) {
                EXPECT_EQ(recorder.primPath(frame.primIds[index]), SdfPath(pixel.prim)) << where << ", primId";
            } else {
                EXPECT_EQ(frame.primIds[index], -1) << where << ", primId";
            }
            EXPECT_EQ(frame.instanceIds[index], covered ? 0 : -1) << where << ", instanceId";
            EXPECT_EQ(frame.elementIds[index], pixel.elementId) << where << ", elementId";
        }
    }
}

namespace {

// A mesh of `counts` faces over `points`, as a Mesh prim at `path`.
UsdGeomMesh defineMesh(UsdStageRefPtr const& stage, std::string const& path, VtVec3fArray const& points,
                       VtIntArray const& counts, VtIntArray const& indices, TfToken const& scheme) {
    UsdGeomMesh mesh = UsdGeomMesh::Define(stage, SdfPath(path));
    mesh.CreatePointsAttr(VtValue(points));
    mesh.CreateFaceVertexCountsAttr(VtValue(counts));
    mesh.CreateFaceVertexIndicesAttr(VtValue(indices));
    mesh.CreateSubdivisionSchemeAttr(VtValue(scheme));
    return mesh;
}

// A 2 x 2 grid of `size`-unit quads centred on the origin in the z = 0
// plane, faces counter-clockwise from +z: 0 bottom left, 1 bottom right,
// 2 top left, 3 top right.
UsdGeomMesh defineGrid(UsdStageRefPtr const& stage, std::string const& path, float size) {
    VtVec3fArray points;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) points.push_back(GfVec3f(size * float(x - 1), size * float(y - 1), 0.0f));
    return defineMesh(stage, path, points, {4, 4, 4, 4}, {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7},
                      UsdGeomTokens->none);
}

// The cube [-1, 1]^3, right-handed, catmullClark.
UsdGeomMesh defineCube(UsdStageRefPtr const& stage, std::string const& path) {
    VtVec3fArray points;
    for (int i = 0; i < 8; ++i)
        points.push_back(GfVec3f((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f));
    return defineMesh(stage, path, points, {4, 4, 4, 4, 4, 4},
                      {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5},
                      UsdGeomTokens->catmullClark);
}

// The frame's pixel (bottom-up, as Hydra's buffers run) nearest to where the
// world point (x, y, z) projects through cameraAndLightStage's camera
// (z = 10, aperture 20.955 x 15.2908 mm, focal length 50, 64 x 48 pixels).
size_t pixelOf(Frame const& frame, double x, double y, double z) {
    const double d = 10.0 - z;
    const double column = 32.0 + x * 64.0 / (d * 20.955 / 50.0);
    const double row = 24.0 + y * 64.0 / (d * 20.955 / 50.0);  // square pixels
    return size_t(int(row) * frame.width + int(column));
}

}  // namespace

// A mesh through Hydra, in every transparency mode: drawn over the strand
// behind it with its faces' uniform colours, its depth, its primId and the
// face as elementId; the strand off the mesh as before.
TEST_F(HdHairPlugin, MeshesHideHairAndNameTheirFacesInEveryAov) {
    UsdStageRefPtr stage = cameraAndLightStage();
    UsdGeomMesh grid = defineGrid(stage, "/Grid", 1.0f);
    grid.AddTranslateOp().Set(GfVec3d(0, 0, 2));
    const VtVec3fArray faceColors = {GfVec3f(1, 0, 0), GfVec3f(0, 1, 0), GfVec3f(0, 0, 1), GfVec3f(1, 1, 0)};
    grid.CreateDisplayColorPrimvar(UsdGeomTokens->uniform).Set(faceColors);
    defineStrand(stage, "/Behind", GfVec3f(-3, 0.5f, 0), GfVec3f(3, 0.5f, 0), 0.25f);
    Recorder recorder(stage);
    recorder.setSetting("shadingModel", "flat");
    // Window depth at distance d with clipping range [1, 1e6]: f / (f - n) (1 - n / d).
    auto windowDepth = [](double d) { return float(1e6 / (1e6 - 1.0) * (1.0 - 1.0 / d)); };
    for (char const* mode : {"binSorted", "exact", "unsorted", "opaque"}) {
        recorder.setSetting("transparency", mode);
        Frame frame = recorder.render();
        ASSERT_EQ(frame.primIds.size(), frame.color.size() / 4) << mode;
        const double centres[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
        for (int face = 0; face < 4; ++face) {
            // Faces 2 and 3 lie over the strand at y = 0.5: it is hidden.
            const size_t i = pixelOf(frame, centres[face][0], centres[face][1], 2.0);
            const std::string where = std::string(mode) + ", face " + std::to_string(face);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(frame.color[4 * i + size_t(c)], faceColors[size_t(face)][c], 2e-3) << where;
            EXPECT_NEAR(frame.color[4 * i + 3], 1.0f, 2e-3) << where;
            EXPECT_NEAR(frame.depth[i], windowDepth(8.0), 1e-5) << where;
            EXPECT_EQ(recorder.primPath(frame.primIds[i]), SdfPath("/Grid")) << where;
            EXPECT_EQ(frame.instanceIds[i], 0) << where;
            EXPECT_EQ(frame.elementIds[i], face) << where;
        }
        const size_t offMesh = pixelOf(frame, 1.6, 0.5, 0.0);
        EXPECT_EQ(recorder.primPath(frame.primIds[offMesh]), SdfPath("/Behind")) << mode;
        // The strand's own depth (its camera-facing ribbon tilts off-axis
        // by about 1e-5): well behind the mesh's plane.
        EXPECT_NEAR(frame.depth[offMesh], windowDepth(10.0), 1e-4) << mode;
    }
}

// Instanced meshes become one engine prim per instance, as curves do; the
// refine level follows the host's complexity (low: the cage), and holes and
// creases come through the topology and its subdivision tags.
TEST_F(HdHairPlugin, MeshInstancesRefineLevelsHolesAndCreases) {
    UsdStageRefPtr stage = cameraAndLightStage();
    UsdGeomMesh quad = defineGrid(stage, "/Instancer/Prototypes/quad", 0.25f);
    defineInstancer(stage, "/Instancer", {quad.GetPath()}, {0, 0}, {GfVec3f(-1.2f, 0, 0), GfVec3f(1.2f, 0, 0)});
    Recorder instancing(stage);
    Frame instanced = instancing.render();
    const size_t left = pixelOf(instanced, -1.2, 0.1, 0.0), right = pixelOf(instanced, 1.2, 0.1, 0.0);
    EXPECT_EQ(instanced.alpha(int(left % 64), int(left / 64)), 1.0f);
    EXPECT_EQ(instanced.instanceIds[left], 0);
    EXPECT_EQ(instanced.instanceIds[right], 1);
    EXPECT_EQ(instanced.primIds[left], instanced.primIds[right]);
    EXPECT_EQ(instanced.alpha(32, 24), 0.0f) << "the prototype itself was drawn";

    // A catmullClark cube seen face on: the cage at low complexity covers the
    // corner of its square; refined (high), its limit surface does not; with
    // every edge infinitely sharp it keeps its corner; a hole shows nothing.
    UsdStageRefPtr cubes = cameraAndLightStage();
    UsdGeomMesh cube = defineCube(cubes, "/Cube");
    Recorder recorder(cubes);
    auto cornerCovered = [&](float complexity) {
        recorder.setComplexity(complexity);
        Frame frame = recorder.render();
        const size_t i = pixelOf(frame, 0.93, 0.93, 1.0);
        return frame.color[4 * i + 3] > 0.0f;
    };
    EXPECT_TRUE(cornerCovered(1.0f));
    EXPECT_FALSE(cornerCovered(1.2f));
    VtIntArray edges = {0, 1, 1, 3, 3, 2, 2, 0, 4, 5, 5, 7, 7, 6, 6, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    cube.CreateCreaseIndicesAttr(VtValue(edges));
    cube.CreateCreaseLengthsAttr(VtValue(VtIntArray(12, 2)));
    cube.CreateCreaseSharpnessesAttr(VtValue(VtFloatArray(12, 10.0f)));
    EXPECT_TRUE(cornerCovered(1.2f));
    cube.CreateHoleIndicesAttr(VtValue(VtIntArray{1}));  // +z, the face towards the camera
    recorder.setComplexity(1.2f);
    Frame holed = recorder.render();
    const size_t centre = pixelOf(holed, 0.0, 0.0, 1.0);
    // Through the hole: the inside of the -z face, farther away.
    EXPECT_GT(holed.depth[centre], float(1e6 / (1e6 - 1.0) * (1.0 - 1.0 / 10.0)));
    EXPECT_EQ(holed.elementIds[centre], 0);
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
