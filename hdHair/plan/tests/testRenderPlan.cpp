#include <algorithm>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;

namespace {

// The names of what a pass reads, as --explain prints them.
std::vector<std::string> readNames(const RenderPlan& plan, const std::string& pass) {
    return plan.graph().namesOf(plan.graph().find(pass)->reads);
}

LightPrim hostLight() {
    LightPrim light;
    light.path = "/host/light0";
    light.type = LightType::Distant;
    light.hostCameraLight = true;
    // Pointing along +X (its -Z turned to +X): direction towards the light is -X.
    light.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(-90.0), glm::dvec3(0, 1, 0));
    return light;
}

StrandSummary wideOpaqueStrands(uint64_t segments) {
    StrandSummary summary;
    summary.segments = segments;
    summary.allOpaque = true;
    summary.minProjectedWidthPixels = 3.0;
    return summary;
}

CameraView cameraAtPlusZ() {
    CameraView camera;
    camera.view = glm::lookAt(glm::dvec3(0, 0, 5), glm::dvec3(0), glm::dvec3(0, 1, 0));
    return camera;
}

}  // namespace

TEST(RenderPlan, HostCameraLightIsUsedOnlyLikeTheEnginesOwn) {
    Scene scene;
    scene.setLight(hostLight());
    RenderSettings settings;
    RenderPlan alone = makeRenderPlan(scene, settings, cameraAtPlusZ(), wideOpaqueStrands(10));
    ASSERT_TRUE(alone.recipe().lighting.cameraLight);
    ASSERT_EQ(alone.recipe().lighting.lights.lights.size(), 1u);
    EXPECT_NEAR(alone.recipe().lighting.lights.lights[0].directionOrPosition.x, -1.0f, 1e-6f)
        << "the host's light, not a new one";

    LightPrim key;
    key.path = "/World/key";
    scene.setLight(key);
    RenderPlan withStageLight = makeRenderPlan(scene, settings, cameraAtPlusZ(), wideOpaqueStrands(10));
    EXPECT_FALSE(withStageLight.recipe().lighting.cameraLight);
    EXPECT_EQ(withStageLight.recipe().lighting.lights.lights.size(), 1u);

    settings.set("cameraLight", "on");
    EXPECT_EQ(
        makeRenderPlan(scene, settings, cameraAtPlusZ(), wideOpaqueStrands(10)).recipe().lighting.lights.lights.size(),
        2u);
    settings.set("cameraLight", "off");
    EXPECT_EQ(makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), wideOpaqueStrands(10))
                  .recipe()
                  .lighting.lights.lights.size(),
              0u);
}

TEST(RenderPlan, EnginesCameraLightShinesFromTheCamera) {
    RenderPlan plan = makeRenderPlan(Scene{}, RenderSettings{}, cameraAtPlusZ(), wideOpaqueStrands(10));
    ASSERT_EQ(plan.recipe().lighting.lights.lights.size(), 1u);
    EXPECT_NEAR(plan.recipe().lighting.lights.lights[0].directionOrPosition.z, 1.0f, 1e-6f);
    EXPECT_TRUE(plan.isEnabled("strands"));
    EXPECT_FALSE(makeRenderPlan(Scene{}, RenderSettings{}, cameraAtPlusZ(), wideOpaqueStrands(0)).isEnabled("strands"));
}

TEST(RenderPlan, OnlyStagesThatNeedBlendingAreSorted) {
    RenderSettings settings;
    settings.set("strandRaster", "hardware");  // the bin sort serves the hardware rasteriser
    RenderPlan wide = makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), wideOpaqueStrands(10));
    EXPECT_EQ(wide.recipe().transparency.path, TransparencyPath::Opaque);
    EXPECT_FALSE(wide.isEnabled("sort"));

    StrandSummary thin = wideOpaqueStrands(10);
    thin.minProjectedWidthPixels = 0.5;  // sub-pixel: coverage needs blending
    RenderPlan sorted = makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), thin);
    EXPECT_EQ(sorted.recipe().transparency.path, TransparencyPath::BinSorted);
    EXPECT_TRUE(sorted.isEnabled("sort"));
    EXPECT_EQ(sorted.recipe().transparency.sortBins, 256u);

    StrandSummary translucent = wideOpaqueStrands(10);
    translucent.allOpaque = false;
    settings.set("transparency", "exact");
    EXPECT_EQ(makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), translucent).recipe().transparency.path,
              TransparencyPath::Exact);
    settings.set("transparency", "unsorted");
    EXPECT_EQ(makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), translucent).recipe().transparency.path,
              TransparencyPath::Unsorted);
    settings.set("transparency", "opaque");
    EXPECT_EQ(makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), translucent).recipe().transparency.path,
              TransparencyPath::Opaque);
}

TEST(RenderPlan, MsaaAppliesToTheOpaquePathOnly) {
    RenderSettings settings;
    settings.set("msaaSamples", "4");
    EXPECT_EQ(
        makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), wideOpaqueStrands(10)).recipe().transparency.msaaSamples, 4);
    StrandSummary thin = wideOpaqueStrands(10);
    thin.minProjectedWidthPixels = 0.5;
    EXPECT_EQ(makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), thin).recipe().transparency.msaaSamples, 0);
}

TEST(RenderPlan, SaysWhichPassProducesDepthAndIds) {
    StrandSummary translucent = wideOpaqueStrands(10);
    translucent.allOpaque = false;
    auto plan = [&](const char* transparency, bool ids) {
        RenderSettings settings;
        settings.set("transparency", transparency);
        settings.set("strandRaster", "hardware");  // compute: AutoRasterisesThinBlendedStrandsInComputeAndSaysWhy
        return makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), translucent, ids);
    };
    auto strandsReason = [](const RenderPlan& p) { return p.graph().find("strands")->reason; };
    // Blended paths other than exact draw ids in a pass of their own, only when asked for.
    for (const char* path : {"binSorted", "unsorted"}) {
        EXPECT_TRUE(plan(path, true).isEnabled("ids")) << path;
        EXPECT_FALSE(plan(path, false).isEnabled("ids")) << path;
        EXPECT_NE(strandsReason(plan(path, false)).find("depth: the nearest fragment with alpha >= 0.1, min-blended"),
                  std::string::npos)
            << path;
    }
    RenderPlan exact = plan("exact", true);
    EXPECT_FALSE(exact.isEnabled("ids"));
    EXPECT_NE(strandsReason(exact).find("depth and ids: the nearest listed fragment with alpha >= 0.1"),
              std::string::npos);
    RenderPlan opaque = plan("opaque", true);
    EXPECT_FALSE(opaque.isEnabled("ids"));
    EXPECT_NE(strandsReason(opaque).find("depth: the depth buffer"), std::string::npos);

    // Exact over its memory: the frame is planned again bin sorted, which
    // needs the ids pass.
    auto replanned = [&](bool ids) {
        RenderSettings settings;
        settings.set("transparency", "exact");
        settings.set("strandRaster", "hardware");
        PlanRequest request;
        request.idsRequested = ids;
        EXPECT_TRUE(request.fallbacks.add({FrameFallback::Kind::ExactListsOverBudget, "exact -> binSorted", ""}));
        EXPECT_FALSE(request.fallbacks.add({FrameFallback::Kind::ExactListsOverBudget, "exact -> binSorted", ""}));
        return makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), translucent, {}, {}, request);
    };
    RenderPlan fellBack = replanned(true);
    EXPECT_EQ(fellBack.recipe().transparency.path, TransparencyPath::BinSorted);
    EXPECT_EQ(fellBack.recipe().transparency.sortBins, 1024u);
    EXPECT_TRUE(fellBack.isEnabled("sort"));
    EXPECT_TRUE(fellBack.isEnabled("ids"));
    EXPECT_NE(fellBack.recipe().transparency.reason.find("exact fell back"), std::string::npos)
        << fellBack.recipe().transparency.reason;
    EXPECT_FALSE(replanned(false).isEnabled("ids"));
}

TEST(RenderPlan, AutoRasterisesThinBlendedStrandsInComputeAndSaysWhy) {
    StrandSummary thin = wideOpaqueStrands(10);
    thin.minProjectedWidthPixels = 0.4;
    thin.maxProjectedWidthPixels = 1.5;
    auto plan = [&](std::vector<std::string> assignments, const StrandSummary& strands, bool ids = false,
                    bool computeListsOverBudget = false) {
        RenderSettings settings;
        for (const std::string& assignment : assignments) settings.setFromAssignment(assignment);
        PlanRequest request;
        request.idsRequested = ids;
        if (computeListsOverBudget)
            request.fallbacks.add({FrameFallback::Kind::ComputeListsOverBudget, "compute -> hardware", ""});
        return makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), strands, {}, {}, request);
    };
    auto strandsReason = [](const RenderPlan& p) { return p.graph().find("strands")->reason; };

    // auto is the default.
    RenderPlan automatic = plan({}, thin, true);
    EXPECT_EQ(automatic.recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(automatic.recipe().transparency.path, TransparencyPath::BinSorted);
    EXPECT_NE(strandsReason(automatic).find("compute: the strands project at most 1.50 px wide and cover about "
                                            "0.0 px a span or fewer (strandRasterMaxPixelWidth 4, "
                                            "strandRasterMaxFragmentsPerSpan 20; strandRaster=auto)"),
              std::string::npos)
        << strandsReason(automatic);
    // Lists sorted per pixel: no bin sort, no draw order, ids from the resolve.
    EXPECT_FALSE(automatic.isEnabled("sort"));
    EXPECT_FALSE(automatic.isEnabled("ids"));
    const std::vector<FrameResource>& reads = automatic.graph().find("strands")->reads;
    EXPECT_EQ(std::find(reads.begin(), reads.end(), FrameResource(ResourceKind::DrawOrder)), reads.end());
    EXPECT_NE(strandsReason(automatic).find("depth and ids: the nearest listed fragment"), std::string::npos);

    // Over its memory budget the frame is planned again on the hardware path
    // with the transparency planned: binSorted needs its sort and, with ids,
    // the ids pass.
    RenderPlan fellBack = plan({}, thin, true, true);
    EXPECT_EQ(fellBack.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_TRUE(fellBack.isEnabled("sort"));
    EXPECT_TRUE(fellBack.isEnabled("ids"));
    EXPECT_NE(fellBack.recipe().strandRaster.reason.find("hardware: the compute rasteriser's lists were over "
                                                         "strandRasterMemoryMB=512"),
              std::string::npos)
        << fellBack.recipe().strandRaster.reason;

    StrandSummary wide = thin;
    wide.maxProjectedWidthPixels = 6.0;
    RenderPlan wideAuto = plan({"strandRaster=auto"}, wide);
    EXPECT_EQ(wideAuto.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_NE(wideAuto.recipe().strandRaster.reason.find("hardware: the strands may project 6.00 px wide ("),
              std::string::npos)
        << wideAuto.recipe().strandRaster.reason;
    EXPECT_EQ(plan({"strandRaster=auto", "strandRasterMaxPixelWidth=8"}, wide).recipe().strandRaster.rasteriser,
              StrandRaster::Compute);
    StrandSummary justOver = thin;
    justOver.maxProjectedWidthPixels = 4.1;
    EXPECT_EQ(plan({"strandRaster=auto"}, justOver).recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    // An approximation asked for by a value other than the default keeps
    // the hardware path; the defaults (which Hydra hosts echo back as if
    // set) and exact, which the compute lists give too, do not.
    RenderPlan unsorted = plan({"transparency=unsorted"}, thin);
    EXPECT_EQ(unsorted.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_NE(unsorted.recipe().strandRaster.reason.find("hardware: transparency=unsorted is set"), std::string::npos)
        << unsorted.recipe().strandRaster.reason;
    EXPECT_EQ(plan({"sortBins=16"}, thin).recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_EQ(plan({"sortBins=16", "transparency=exact"}, thin).recipe().strandRaster.rasteriser,
              StrandRaster::Compute);
    EXPECT_EQ(plan({"transparency=binSorted"}, thin).recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(plan({"sortBins=256"}, thin).recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(plan({"transparency=exact"}, thin).recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(plan({"transparency=unsorted", "strandRaster=compute"}, thin).recipe().strandRaster.rasteriser,
              StrandRaster::Compute);
    StrandSummary reachesCamera = thin;
    reachesCamera.maxProjectedWidthPixels = std::numeric_limits<double>::infinity();
    EXPECT_EQ(plan({"strandRaster=auto"}, reachesCamera).recipe().strandRaster.rasteriser, StrandRaster::Hardware);

    // Per prim: the thin ones in compute, the wide ones listed by the
    // hardware into the same lists, while the thin hold at least half the
    // segments; else the whole frame on the hardware.
    StrandSummary mixed = thin;
    mixed.maxProjectedWidthPixels = 9.0;
    mixed.prims = {{1.5, 600, 4.0}, {9.0, 100, 30.0}, {0.5, 300, 2.0}};
    RenderPlan mixedAuto = plan({}, mixed, true);
    EXPECT_EQ(mixedAuto.recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(mixedAuto.recipe().strandRaster.listedByHardware, (std::vector<bool>{false, true, false}));
    EXPECT_TRUE(mixedAuto.recipe().strandRaster.mixesRasterisers());
    EXPECT_FALSE(mixedAuto.isEnabled("sort"));
    EXPECT_NE(
        mixedAuto.recipe().strandRaster.reason.find("compute for 2 of 3 prims (900 of 1000 segments), whose strands "
                                                    "project at most 1.50 px wide and cover about 4.0 px a span or "
                                                    "fewer; the hardware rasteriser lists the 1 other prim(s), whose "
                                                    "strands may project 9.00 px wide, into the same lists"),
        std::string::npos)
        << mixedAuto.recipe().strandRaster.reason;
    EXPECT_FALSE(plan({}, mixed, true, true).recipe().strandRaster.mixesRasterisers());
    mixed.prims = {{1.5, 400, 4.0}, {std::numeric_limits<double>::infinity(), 600, 4.0}};
    RenderPlan mostlyWide = plan({}, mixed);
    EXPECT_EQ(mostlyWide.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_TRUE(mostlyWide.recipe().strandRaster.listedByHardware.empty());
    EXPECT_NE(
        mostlyWide.recipe().strandRaster.reason.find("hardware: the strands reach the camera's plane, so no width "
                                                     "bounds them; the prims within the rule hold under half the "
                                                     "segments"),
        std::string::npos)
        << mostlyWide.recipe().strandRaster.reason;
    mixed.prims = {{1.5, 500, 4.0}, {std::numeric_limits<double>::infinity(), 500, 4.0}};
    EXPECT_EQ(plan({}, mixed).recipe().strandRaster.listedByHardware, (std::vector<bool>{false, true}));
    EXPECT_FALSE(plan({"strandRaster=compute"}, mixed).recipe().strandRaster.mixesRasterisers());
    EXPECT_FALSE(plan({"strandRaster=hardware"}, mixed).recipe().strandRaster.mixesRasterisers());
    // Thin strands whose spans cover many pixels (long spans across the
    // frame) keep the hardware: the compute rasteriser's cost follows the
    // fragments it lists.
    StrandSummary longSpans = thin;
    longSpans.prims = {{1.5, 1000, 56.6}};
    RenderPlan coveringMany = plan({}, longSpans);
    EXPECT_EQ(coveringMany.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_NE(coveringMany.recipe().strandRaster.reason.find("hardware: the strands cover about 56.6 px a span ("),
              std::string::npos)
        << coveringMany.recipe().strandRaster.reason;
    EXPECT_EQ(plan({"strandRasterMaxFragmentsPerSpan=60"}, longSpans).recipe().strandRaster.rasteriser,
              StrandRaster::Compute);
    longSpans.prims.push_back({1.5, 1000, 3.0});
    EXPECT_EQ(plan({}, longSpans).recipe().strandRaster.listedByHardware, (std::vector<bool>{true, false}));

    // Asked for, compute takes any blended frame; never the opaque path.
    EXPECT_EQ(plan({"strandRaster=compute"}, wide).recipe().strandRaster.rasteriser, StrandRaster::Compute);
    EXPECT_EQ(plan({"strandRaster=hardware"}, thin).recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    RenderPlan opaque = plan({"strandRaster=compute"}, wideOpaqueStrands(10));
    EXPECT_EQ(opaque.recipe().transparency.path, TransparencyPath::Opaque);
    EXPECT_EQ(opaque.recipe().strandRaster.rasteriser, StrandRaster::Hardware);
    EXPECT_TRUE(plan({"strandRaster=hardware"}, thin).isEnabled("sort"));
}

// A stage without meshes builds neither mesh pass; one with visible meshes
// draws them before the strands, sends them only when one changed, and has
// later light batches draw them again.
TEST(RenderPlan, MeshPassesRunOnlyForVisibleMeshes) {
    RenderSettings settings;
    settings.set("transparency", "binSorted");
    settings.set("strandRaster", "hardware");  // whose light batches read the draw order
    settings.set("lightsPerPass", "1");
    Scene scene;
    for (const char* path : {"/key", "/fill"}) {
        LightPrim light;
        light.path = path;
        scene.setLight(light);
    }
    StrandSummary thin = wideOpaqueStrands(10);
    thin.allOpaque = false;
    const RenderPlan hairOnly = makeRenderPlan(scene, settings, cameraAtPlusZ(), thin, true);
    for (const char* pass : {"meshUpload", "meshes"}) {
        ASSERT_NE(hairOnly.graph().find(pass), nullptr);
        EXPECT_FALSE(hairOnly.graph().find(pass)->wanted) << pass;
        EXPECT_FALSE(hairOnly.isEnabled(pass)) << pass;
    }
    EXPECT_EQ(hairOnly.graph().find("meshes")->reason, "no meshes");
    EXPECT_EQ(readNames(hairOnly, "lightBatch 2"), (std::vector<std::string>{"strands", "drawOrder", "color"}));

    MeshSummary meshes;
    meshes.meshes = 2;
    meshes.triangles = 960;
    meshes.minRefineLevel = 0;
    meshes.maxRefineLevel = 2;
    meshes.changed = true;
    MeshPrim mesh;
    mesh.path = "/head";
    scene.setMesh(mesh);
    const RenderPlan withMeshes = makeRenderPlan(scene, settings, cameraAtPlusZ(), thin, true, meshes);
    EXPECT_TRUE(withMeshes.isEnabled("meshUpload"));
    EXPECT_TRUE(withMeshes.isEnabled("meshes"));
    EXPECT_TRUE(withMeshes.recipe().lighting.meshesLit);
    EXPECT_EQ(withMeshes.graph().find("meshes")->reason,
              "2 mesh(es), 960 triangles (refine levels 0-2), opaque, Lambert under the lights; drawn before the "
              "strands: depth and ids written, strands behind them hidden");
    std::vector<std::string> order;
    for (const FramePass& pass : withMeshes.graph().passes())
        if (pass.enabled) order.push_back(pass.name);
    EXPECT_EQ(order, (std::vector<std::string>{"upload", "meshUpload", "sort", "clear", "meshes", "strands", "ids",
                                               "lightBatch 2", "readback"}));
    EXPECT_EQ(readNames(withMeshes, "lightBatch 2"),
              (std::vector<std::string>{"strands", "drawOrder", "meshGeometry", "color"}));

    // Meshes alone: no strand pass, the meshes still lit in both batches.
    const RenderPlan meshesOnly = makeRenderPlan(scene, settings, cameraAtPlusZ(), StrandSummary{}, false, meshes);
    EXPECT_FALSE(meshesOnly.isEnabled("strands"));
    EXPECT_TRUE(meshesOnly.isEnabled("meshes"));
    EXPECT_TRUE(meshesOnly.isEnabled("lightBatch 2"));
    EXPECT_EQ(readNames(meshesOnly, "lightBatch 2"), (std::vector<std::string>{"meshGeometry", "color"}));

    // shadingModel=flat: meshes unlit, and without lit hair no lights at all.
    settings.set("shadingModel", "flat");
    StrandSummary flatHair = thin;
    flatHair.anyLit = false;
    const RenderPlan flat = makeRenderPlan(scene, settings, cameraAtPlusZ(), flatHair, false, meshes);
    EXPECT_FALSE(flat.recipe().lighting.meshesLit);
    EXPECT_TRUE(flat.recipe().lighting.flatShading);
    EXPECT_EQ(flat.recipe().lighting.batches.size(), 1u);
}

namespace {

StrandSummary castingStrands() {
    StrandSummary summary = wideOpaqueStrands(10);
    summary.casters.min = glm::dvec3(-1.0);
    summary.casters.max = glm::dvec3(1.0);
    return summary;
}

LightPrim distantLight(const std::string& path, bool casts = true) {
    LightPrim light;
    light.path = path;
    light.shadowEnable = casts;
    return light;
}

std::vector<std::string> shadowPassNames(const RenderPlan& plan) {
    std::vector<std::string> names;
    for (const FramePass& pass : plan.graph().passes())
        if (pass.name.rfind("shadow", 0) == 0 || pass.name.rfind("deepOpacity", 0) == 0) names.push_back(pass.name);
    return names;
}

bool reads(const RenderPlan& plan, const std::string& pass, const std::string& resource) {
    const std::vector<std::string> names = plan.graph().namesOf(plan.graph().find(pass)->reads);
    return std::find(names.begin(), names.end(), resource) != names.end();
}

}  // namespace

TEST(RenderPlan, EveryCastingLightGetsADepthAndAnOpacityPassReadByItsBatch) {
    Scene scene;
    scene.setLight(distantLight("/key"));
    scene.setLight(distantLight("/rim"));
    RenderSettings settings;
    settings.set("lightsPerPass", "1");
    RenderPlan plan = makeRenderPlan(scene, settings, cameraAtPlusZ(), castingStrands());
    EXPECT_EQ(shadowPassNames(plan), (std::vector<std::string>{"shadowDepth /key", "deepOpacity /key",
                                                               "shadowDepth /rim", "deepOpacity /rim"}));
    for (const std::string& name : shadowPassNames(plan)) EXPECT_TRUE(plan.isEnabled(name)) << name;
    EXPECT_TRUE(reads(plan, "deepOpacity /key", "hairDepth /key"));
    // Batch 1 shades /key and reads its map only; batch 2 /rim's.
    EXPECT_TRUE(reads(plan, "strands", "deepOpacity /key"));
    EXPECT_FALSE(reads(plan, "strands", "deepOpacity /rim"));
    EXPECT_TRUE(reads(plan, "lightBatch 2", "deepOpacity /rim"));
    EXPECT_EQ(plan.recipe().shadows.lights.size(), 2u);
    EXPECT_TRUE(plan.recipe().shadows.lights[0].view.orthographic);

    EXPECT_TRUE(plan.shadowUsed(0) && plan.shadowUsed(1));

    // The renderer's decisions come in with the plan that runs: a map kept
    // from an earlier frame is an input, its passes do not run and the
    // strands still read it; a rebuilt map says why; a light given no map
    // is read by nothing.
    auto withMaps = [&](std::vector<std::optional<ShadowMapAssignment::Map>> maps) {
        PlanRequest request;
        request.shadowMaps = ShadowMapAssignment{std::move(maps), 2};
        return makeRenderPlan(scene, settings, cameraAtPlusZ(), castingStrands(), {}, {}, request);
    };
    const RenderPlan kept = withMaps({ShadowMapAssignment::Map{0, false, "kept: unchanged"},
                                      ShadowMapAssignment::Map{1, true, "rebuilt: the light moved"}});
    EXPECT_FALSE(kept.isEnabled("shadowDepth /key"));
    EXPECT_FALSE(kept.isEnabled("deepOpacity /key"));
    EXPECT_EQ(kept.graph().find("deepOpacity /key")->reason, "kept: unchanged");
    EXPECT_TRUE(kept.isEnabled("strands"));
    EXPECT_TRUE(reads(kept, "strands", "deepOpacity /key"));
    EXPECT_TRUE(kept.shadowUsed(0));
    EXPECT_TRUE(kept.recipe().shadows.isMapped(kept.recipe().shadows.lights[0]));
    EXPECT_TRUE(kept.isEnabled("deepOpacity /rim"));
    EXPECT_EQ(kept.graph().find("deepOpacity /rim")->reason.rfind("rebuilt: the light moved; ", 0), 0u);
    EXPECT_EQ(kept.recipe().shadows.capacity, 2);

    const RenderPlan unmapped = withMaps({ShadowMapAssignment::Map{-1, false, "no map: over the storage block"},
                                          ShadowMapAssignment::Map{1, true, "rebuilt: new"}});
    EXPECT_FALSE(unmapped.isEnabled("deepOpacity /key"));
    EXPECT_EQ(unmapped.graph().find("deepOpacity /key")->reason, "no map: over the storage block");
    EXPECT_FALSE(reads(unmapped, "strands", "deepOpacity /key"));
    EXPECT_FALSE(unmapped.recipe().shadows.isMapped(unmapped.recipe().shadows.lights[0]));
    EXPECT_TRUE(reads(unmapped, "lightBatch 2", "deepOpacity /rim"));
    // One decision per planned shadow, or the plan is not made.
    EXPECT_THROW(withMaps({ShadowMapAssignment::Map{0, true, "rebuilt"}}), std::logic_error);
}

TEST(RenderPlan, AStageWithNoCastingLightBuildsNoShadowPasses) {
    Scene scene;
    scene.setLight(distantLight("/key", false));
    RenderPlan plan = makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), castingStrands());
    EXPECT_TRUE(shadowPassNames(plan).empty());
    EXPECT_EQ(readNames(plan, "strands"), (std::vector<std::string>{"strands", "color", "depth"}));
}

TEST(RenderPlan, NothingReadsShadowsUnderFlatShadingOrWithShadowsOff) {
    Scene scene;
    scene.setLight(distantLight("/key"));
    StrandSummary flat = castingStrands();
    flat.anyLit = false;
    RenderPlan flatPlan = makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), flat);
    ASSERT_EQ(shadowPassNames(flatPlan).size(), 2u);
    EXPECT_FALSE(flatPlan.isEnabled("shadowDepth /key"));
    EXPECT_FALSE(flatPlan.isEnabled("deepOpacity /key"));
    const std::string flatWhy = flatPlan.describe();
    EXPECT_NE(flatWhy.find("flat-shaded, so no pass reads lights or their shadows; not built: nothing reads its "
                           "output (deepOpacity /key)"),
              std::string::npos)
        << flatWhy;

    RenderSettings off;
    off.set("shadowMode", "off");
    RenderPlan offPlan = makeRenderPlan(scene, off, cameraAtPlusZ(), castingStrands());
    EXPECT_FALSE(offPlan.isEnabled("shadowDepth /key"));
    EXPECT_EQ(offPlan.graph().find("shadowDepth /key")->reason, "shadowMode=off");
    EXPECT_FALSE(reads(offPlan, "strands", "deepOpacity /key"));
}

TEST(RenderPlan, TheReferenceKeepsEveryLightViewFragment) {
    Scene scene;
    scene.setLight(distantLight("/key"));
    RenderSettings settings;
    settings.set("shadowMode", "reference");
    RenderPlan plan = makeRenderPlan(scene, settings, cameraAtPlusZ(), castingStrands());
    EXPECT_EQ(shadowPassNames(plan), std::vector<std::string>{"shadowFragments /key"});
    EXPECT_TRUE(plan.isEnabled("shadowFragments /key"));
    EXPECT_TRUE(reads(plan, "strands", "shadowFragments /key"));
}

// A light inside the hair has no map's view: under deepOpacity it casts
// nothing and says why; under auto (the default) the density volume
// shadows it, and the map's passes say so.
TEST(RenderPlan, ALightInsideTheHairCastsNothingAndSaysWhy) {
    Scene scene;
    LightPrim inside = distantLight("/bulb");
    inside.type = LightType::Sphere;  // at the origin, inside the casters
    scene.setLight(inside);
    RenderSettings mapsOnly;
    mapsOnly.set("shadowMode", "deepOpacity");
    RenderPlan plan = makeRenderPlan(scene, mapsOnly, cameraAtPlusZ(), castingStrands());
    EXPECT_FALSE(plan.isEnabled("shadowDepth /bulb"));
    EXPECT_NE(plan.graph().find("shadowDepth /bulb")->reason.find("no shadows from this light: the light is inside"),
              std::string::npos);
    EXPECT_FALSE(reads(plan, "strands", "deepOpacity /bulb"));
    EXPECT_FALSE(plan.isEnabled("densityVolume"));
    EXPECT_TRUE(plan.isEnabled("strands"));

    RenderPlan volume = makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), castingStrands());
    EXPECT_FALSE(volume.isEnabled("shadowDepth /bulb"));
    EXPECT_NE(volume.graph().find("shadowDepth /bulb")->reason.find("no map: through the hair's density volume"),
              std::string::npos);
    EXPECT_TRUE(volume.isEnabled("densityVolume"));
    EXPECT_TRUE(reads(volume, "strands", "densityVolume"));
}

// Dual scattering's local term reads the density volume by default: the
// volume is built for a light outside the hair that keeps its map, the
// strands read it, and --explain says why. It is not built, and --explain
// says why not, for localTerm=constant, backDensity=0 and shadowMode=off,
// nor without a material where dual scattering runs.
TEST(RenderPlan, DualScatteringsLocalTermReadsTheDensityVolume) {
    Scene scene;
    scene.setLight(distantLight("/key"));
    StrandSummary dual = castingStrands();
    dual.dualScatteringMaterials = 1;
    const RenderPlan plan = makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), dual);
    EXPECT_TRUE(plan.isEnabled("shadowDepth /key"));
    ASSERT_TRUE(plan.isEnabled("densityVolume"));
    EXPECT_TRUE(reads(plan, "strands", "densityVolume"));
    EXPECT_NE(plan.graph().find("densityVolume")->reason.find("hair behind each fibre"), std::string::npos);
    EXPECT_NE(plan.graph().find("strands")->reason.find("multipleScattering:localTerm=densityVolume"),
              std::string::npos);
    const std::pair<const char*, const char*> without[] = {{"multipleScattering:localTerm=constant", "d_b everywhere"},
                                                           {"multipleScattering:backDensity=0", "no local back"},
                                                           {"shadowMode=off", "shadowMode=off builds no density"}};
    for (const auto& [setting, why] : without) {
        RenderSettings settings;
        const std::string text = setting;
        settings.set(text.substr(0, text.find('=')), text.substr(text.find('=') + 1));
        const RenderPlan off = makeRenderPlan(scene, settings, cameraAtPlusZ(), dual);
        EXPECT_FALSE(off.isEnabled("densityVolume")) << setting;
        EXPECT_FALSE(reads(off, "strands", "densityVolume")) << setting;
        EXPECT_NE(off.graph().find("strands")->reason.find(why), std::string::npos) << setting;
    }
    EXPECT_FALSE(makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), castingStrands()).isEnabled("densityVolume"))
        << "no material has dual scattering";
}

// A uniform dome over hair reaches the strands through the density volume
// under shadowMode=auto (no map can: its light has no direction): the
// volume is built, the first batch's strands read it, and --explain says
// so. Not under deepOpacity or off, nor for a dome that casts no shadows.
TEST(RenderPlan, TheUniformDomeReachesTheStrandsThroughTheDensityVolume) {
    LightPrim dome = distantLight("/sky");
    dome.type = LightType::Dome;
    Scene scene;
    scene.setLight(dome);
    const RenderPlan plan = makeRenderPlan(scene, RenderSettings{}, cameraAtPlusZ(), castingStrands());
    ASSERT_TRUE(plan.isEnabled("densityVolume"));
    EXPECT_TRUE(reads(plan, "strands", "densityVolume"));
    EXPECT_NE(plan.graph().find("densityVolume")->reason.find("the uniform dome through the density volume"),
              std::string::npos);
    EXPECT_NE(plan.graph().find("strands")->reason.find("six cones (shadowMode=auto)"), std::string::npos);
    for (const char* mode : {"deepOpacity", "off"}) {
        RenderSettings settings;
        settings.set("shadowMode", mode);
        const RenderPlan unshadowed = makeRenderPlan(scene, settings, cameraAtPlusZ(), castingStrands());
        EXPECT_FALSE(unshadowed.isEnabled("densityVolume")) << mode;
        EXPECT_NE(unshadowed.graph().find("strands")->reason.find("the uniform dome unshadowed"), std::string::npos)
            << mode;
    }
    dome.shadowEnable = false;
    Scene noShadows;
    noShadows.setLight(dome);
    const RenderPlan casting = makeRenderPlan(noShadows, RenderSettings{}, cameraAtPlusZ(), castingStrands());
    EXPECT_FALSE(casting.isEnabled("densityVolume"));
    EXPECT_NE(casting.graph().find("strands")->reason.find("casts no shadows"), std::string::npos);
}

// Like hosts' camera lights, hdHair's casts no shadow unless asked: a light
// at the eye darkens only what the eye cannot see, at the cost of a map.
TEST(RenderPlan, TheCameraLightCastsOnlyWhenAsked) {
    const RenderPlan unshadowed = makeRenderPlan(Scene{}, RenderSettings{}, cameraAtPlusZ(), castingStrands());
    ASSERT_TRUE(unshadowed.recipe().lighting.cameraLight);
    EXPECT_TRUE(unshadowed.recipe().shadows.lights.empty());
    EXPECT_TRUE(shadowPassNames(unshadowed).empty());
    EXPECT_NE(unshadowed.describe().find("incl. the camera light, which casts no shadow (cameraLightShadows)"),
              std::string::npos)
        << unshadowed.describe();
    RenderSettings settings;
    settings.set("cameraLightShadows", "on");
    RenderPlan plan = makeRenderPlan(Scene{}, settings, cameraAtPlusZ(), castingStrands());
    ASSERT_TRUE(plan.recipe().lighting.cameraLight);
    EXPECT_EQ(shadowPassNames(plan), (std::vector<std::string>{"shadowDepth camera light", "deepOpacity camera light"}));
    EXPECT_TRUE(reads(plan, "strands", "deepOpacity camera light"));
}

// RenderPlan.h lists the passes for the next engineer, one kind a line:
// every kind, in PassKind's order, and nothing else.
TEST(RenderPlan, ThePassListHereIsEveryKindInOrder) {
    std::ifstream header(std::string(HDHAIR_SOURCE_DIR) + "/hdHair/plan/RenderPlan.h");
    ASSERT_TRUE(header) << "RenderPlan.h";
    std::vector<std::string> listed;
    bool inList = false;
    for (std::string line; std::getline(header, line);) {
        if (line.rfind("// The passes, in the order they run", 0) == 0) inList = true;
        else if (inList && line.rfind("//   ", 0) != 0 && line.rfind("// ", 0) != 0) break;
        if (!inList || line.rfind("//   ", 0) != 0 || line.size() < 6 || line[5] == ' ') continue;
        std::istringstream words(line.substr(5));
        std::string name;
        words >> name;
        listed.push_back(name);
    }
    EXPECT_EQ(listed, tokenNames<PassKind>());
}

// Each planner returns its own plan from the plans it depends on: what a
// later planner decides follows from what it is given, not from the order
// planners happened to run in on a shared recipe.
TEST(RenderPlan, PlannersDecideFromThePlansTheyAreGiven) {
    RenderSettings settings;
    settings.set("strandRaster", "compute");
    settings.set("minPixelWidth", "1.5");
    settings.set("tessellation", "projectedLength");
    TransparencyPlan opaque;
    opaque.path = TransparencyPath::Opaque;
    TransparencyPlan blended;
    blended.path = TransparencyPath::Exact;
    const StrandSummary strands = wideOpaqueStrands(10);
    const FrameFallbacks none;

    // The opaque path is the hardware's whatever strandRaster asks for.
    EXPECT_EQ(planStrandRaster(opaque, settings.values(), strands, "", none).rasteriser, StrandRaster::Hardware);
    EXPECT_EQ(planStrandRaster(blended, settings.values(), strands, "", none).rasteriser, StrandRaster::Compute);

    // The coverage rule applies where strands blend; projectedLength has no
    // chord tolerance.
    EXPECT_EQ(planTessellation(settings.values(), opaque).minPixelWidth, 0.0);
    EXPECT_EQ(planTessellation(settings.values(), blended).minPixelWidth, 1.5);
    EXPECT_EQ(planTessellation(settings.values(), blended).tolerance, 0.0);
    settings.set("tessellation", "screenError");
    settings.set("tessellationTolerance", "0.25");
    EXPECT_EQ(planTessellation(settings.values(), blended).tolerance, 0.25);

    // The shadows read the lights' plan: a light that casts gets a planned
    // shadow, and the SRBF lights' shared maps come from the lights.
    LightPlan lights;
    lights.lights.lights.resize(3);
    lights.lights.lights[0].castsShadow = true;
    lights.lights.lights[1].castsShadow = false;  // an SRBF light reading light 0's map
    lights.lights.lights[2].castsShadow = true;
    lights.sharedMaps = {{1, 0}};
    settings.set("shadowMode", "deepOpacity");
    const ShadowPlan shadows = planShadows(lights, settings.values(), strands, MeshSummary{}, std::nullopt);
    ASSERT_EQ(shadows.lights.size(), 2u);
    EXPECT_EQ(shadows.lights[1].light, 2u);
    EXPECT_EQ(shadows.shadowOf(1), 0);
    EXPECT_EQ(shadows.shadowOf(2), 1);
}

// A recipe is made once and held, read-only, by its plan.
TEST(RenderPlan, HoldsItsRecipeReadOnly) {
    static_assert(std::is_same_v<decltype(std::declval<const RenderPlan&>().recipe()), const FrameRecipe&>);
    static_assert(!std::is_base_of_v<FrameRecipe, RenderPlan>);
    RenderSettings settings;
    settings.set("lightsPerPass", "2");
    Scene scene;
    for (const char* path : {"/a", "/b", "/c"}) {
        LightPrim light;
        light.path = path;
        light.type = LightType::Distant;
        scene.setLight(light);
    }
    const RenderPlan plan = makeRenderPlan(scene, settings, cameraAtPlusZ(), wideOpaqueStrands(10));
    EXPECT_EQ(plan.recipe().lighting.batches.size(), 2u);
    EXPECT_TRUE(plan.isEnabled(PassKind::LightBatch, 1));
}
