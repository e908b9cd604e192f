// The Renderer on scenes built in code: id outputs for picking, and what a
// frame costs when nothing asks for them.

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/gl/SoftwareRenderer.h"
#include "hdHair/gl/tests/MachineGpu.h"
#include "hdHair/image/BoxDownsample.h"
#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/render/tests/SquareCamera.h"
#include "hdHair/render/SupersampleResolve.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;
using hdhair::test::squareCamera;

namespace {

// Horizontal linear strands at heights y, one curve each, 0.2 wide, in the
// plane z = 0, from x = -1 to 1.
CurvesPrim horizontalStrands(const std::string& path, int primId, const std::vector<float>& heights) {
    CurvesPrim prim;
    prim.path = path;
    prim.primId = primId;
    prim.type = CurveType::Linear;
    for (float y : heights) {
        prim.curveVertexCounts.push_back(2);
        prim.points.push_back({-1.0f, y, 0.0f});
        prim.points.push_back({1.0f, y, 0.0f});
    }
    Primvar widths;
    widths.name = "widths";
    widths.values = {0.2f};
    prim.primvars["widths"] = widths;
    return prim;
}

int pixelRow(const CameraView& camera, float y) {
    return int(camera.worldToPixel(glm::dvec3(0.0, y, 0.0)).y);
}

}  // namespace

TEST(Renderer, IdOutputsNamePrimAndCurveUnderEachPixel) {
    Scene scene;
    scene.setCurves(horizontalStrands("/a", 7, {0.8f, 0.4f}));
    scene.setCurves(horizontalStrands("/b", 9, {-0.4f, -0.8f}));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    CameraView camera = squareCamera(96);
    RenderResult result = renderer.render(scene, camera, RenderSettings{}, diagnostics, RenderOutputs{true});
    ASSERT_EQ(result.primIds.size(), size_t(96 * 96));
    auto at = [&](const std::vector<int32_t>& ids, float y) { return ids[size_t(pixelRow(camera, y)) * 96 + 48]; };
    EXPECT_EQ(at(result.primIds, 0.8f), 7);
    EXPECT_EQ(at(result.elementIds, 0.8f), 0);
    EXPECT_EQ(at(result.elementIds, 0.4f), 1);
    EXPECT_EQ(at(result.primIds, -0.4f), 9);
    EXPECT_EQ(at(result.elementIds, -0.4f), 0);
    EXPECT_EQ(at(result.elementIds, -0.8f), 1);
    EXPECT_EQ(at(result.instanceIds, -0.8f), 0);
    // Between strands there is nothing: -1, Hydra's empty id.
    EXPECT_EQ(at(result.primIds, 0.0f), -1);
    EXPECT_EQ(at(result.elementIds, 0.0f), -1);
    EXPECT_EQ(at(result.instanceIds, 0.0f), -1);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(Renderer, IdOutputsNameTheInstanceInEveryTransparencyMode) {
    // Instances of one prim (as the Hydra plugin expands them) share the
    // prim id and differ by instance id; the exact mode and the compute
    // rasteriser resolve ids from their fragment lists rather than from the
    // strand pass.
    Scene scene;
    CurvesPrim first = horizontalStrands("/proto{0}", 5, {0.5f});
    CurvesPrim second = horizontalStrands("/proto{1}", 5, {0.5f});
    second.instanceId = 1;
    second.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -1.0, 0.0));
    for (CurvesPrim* prim : {&first, &second}) prim->primvars["displayOpacity"].values = {0.6f};
    scene.setCurves(first);
    scene.setCurves(second);
    Renderer renderer(gl::GlBackend::Egl);
    CameraView camera = squareCamera(64);
    for (const char* mode : {"binSorted", "exact", "unsorted", "opaque", "compute"}) {
        RenderSettings settings;
        settings.set(mode == std::string("compute") ? "strandRaster" : "transparency", mode);
        Diagnostics diagnostics;
        RenderResult result = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
        EXPECT_EQ(result.stats.strandRaster, mode == std::string("compute") ? "compute" : "hardware") << mode;
        auto at = [&](const std::vector<int32_t>& ids, float y) { return ids[size_t(pixelRow(camera, y)) * 64 + 32]; };
        EXPECT_EQ(at(result.primIds, 0.5f), 5) << mode;
        EXPECT_EQ(at(result.instanceIds, 0.5f), 0) << mode;
        EXPECT_EQ(at(result.primIds, -0.5f), 5) << mode;
        EXPECT_EQ(at(result.instanceIds, -0.5f), 1) << mode;
        EXPECT_EQ(at(result.elementIds, -0.5f), 0) << mode;
        EXPECT_EQ(at(result.instanceIds, 0.0f), -1) << mode;
        EXPECT_TRUE(diagnostics.warnings().empty()) << mode;
    }
}

TEST(Renderer, AMaterialEditRecoloursItsPrimsWithoutTouchingThem) {
    Scene scene;
    CurvesPrim prim = horizontalStrands("/a", 1, {0.0f});
    prim.materialBinding = "/Looks/hair";
    scene.setCurves(prim);
    MaterialPrim material;
    material.path = "/Looks/hair";
    material.surfaceShaderId = "UsdPreviewSurface";
    material.diffuseColor.value = {1.0f, 0.0f, 0.0f};
    scene.setMaterial(material);
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderSettings flat;
    flat.set("shadingModel", "flat");
    CameraView camera = squareCamera(32);
    auto centre = [&](const RenderResult& result) {
        const float* pixel = &result.color.pixels[(size_t(pixelRow(camera, 0.0f)) * 32 + 16) * 4];
        return glm::vec3(pixel[0], pixel[1], pixel[2]);
    };
    glm::vec3 red = centre(renderer.render(scene, camera, flat, diagnostics));
    EXPECT_GT(red.r, 0.5f);
    EXPECT_LT(red.g, 0.01f);
    const uint64_t primVersion = scene.curves().at("/a").version;
    material.diffuseColor.value = {0.0f, 1.0f, 0.0f};
    scene.setMaterial(material);
    glm::vec3 green = centre(renderer.render(scene, camera, flat, diagnostics));
    EXPECT_EQ(scene.curves().at("/a").version, primVersion);
    EXPECT_LT(green.r, 0.01f);
    EXPECT_GT(green.g, 0.5f);
    // Unbinding (the material removed) brings back the fallback grey.
    scene.remove("/Looks/hair");
    glm::vec3 grey = centre(renderer.render(scene, camera, flat, diagnostics));
    EXPECT_NEAR(grey.r, grey.g, 1e-3f);
    EXPECT_GT(grey.r, 0.1f);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(Renderer, ElementIdsSurviveDrawBatching) {
    // Many curves in one prim are drawn in several batches; gl_PrimitiveID
    // restarts in each, so the batch's first segment must be added back.
    std::vector<float> heights;
    for (int i = 0; i < 300; ++i) heights.push_back(-1.0f + 2.0f * float(i) / 299.0f);
    Scene scene;
    CurvesPrim many = horizontalStrands("/many", 3, heights);
    many.primvars["widths"].values = {0.04f};  // about a pixel, overlapping neighbours
    scene.setCurves(many);
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    CameraView camera = squareCamera(64);
    RenderSettings settings;
    settings.set("maxSegmentsPerSpan", "64");  // 130 vertices a patch: 15 patches a batch
    RenderResult result = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    // Curve i lies at height -1 + 2i/299: down the centre column the ids must
    // fall steadily from the last curve to the first. Ids restarting at each
    // batch would break the order.
    int previous = 1 << 30, covered = 0;
    for (int row = 0; row < 64; ++row) {
        int id = result.elementIds[size_t(row) * 64 + 32];
        if (id < 0) continue;
        ++covered;
        EXPECT_LE(id, previous) << "row " << row;
        previous = id;
    }
    EXPECT_GT(covered, 50);
    EXPECT_GT(result.elementIds[size_t(pixelRow(camera, 0.99f)) * 64 + 32], 290);
    EXPECT_LT(result.elementIds[size_t(pixelRow(camera, -0.99f)) * 64 + 32], 10);
}

TEST(Renderer, BatchedDrawsGiveTheSameImageAsOneDrawARange) {
    // Batching exists for llvmpipe (hdHair/gl/PatchBatching.h); it must not
    // change what is drawn: colour, depth and ids equal, bit for bit, with a
    // scene small enough for llvmpipe's unbatched draws (300 patches in 10
    // batches of 31 at 32 segments a span), sorted and opaque.
    std::vector<float> heights;
    for (int i = 0; i < 300; ++i) heights.push_back(-1.0f + 2.0f * float(i) / 299.0f);
    Scene scene;
    CurvesPrim many = horizontalStrands("/many", 3, heights);
    many.type = CurveType::Cubic;
    many.basis = CurveBasis::CatmullRom;
    many.curveVertexCounts.assign(100, 6);  // 100 wavy curves of 3 spans
    for (size_t i = 0; i < many.points.size(); ++i) many.points[i].z = 0.3f * std::sin(float(i));
    many.primvars["widths"].values = {0.03f};
    scene.setCurves(many);
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    CameraView camera = squareCamera(64);
    for (const char* transparency : {"binSorted", "opaque"}) {
        SCOPED_TRACE(transparency);
        RenderSettings settings;
        settings.set("maxSegmentsPerSpan", "32");
        settings.set("tessellation", "projectedLength");
        settings.set("pixelsPerSegment", "0.25");
        settings.set("transparency", transparency);
        settings.set("strandRaster", "hardware");  // the draws batching splits
        settings.set("drawBatching", "on");
        RenderResult batched = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
        settings.set("drawBatching", "off");
        RenderResult whole = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
        EXPECT_NE(batched.stats.drawBatching.find("at most 2048"), std::string::npos) << batched.stats.drawBatching;
        EXPECT_NE(whole.stats.drawBatching.find("one draw a prim range"), std::string::npos);
        EXPECT_GT(whole.stats.strandTriangles, 300u * 30u);
        EXPECT_EQ(batched.stats.strandTriangles, whole.stats.strandTriangles);
        EXPECT_EQ(batched.color.pixels, whole.color.pixels);
        EXPECT_EQ(batched.depth.pixels, whole.depth.pixels);
        EXPECT_EQ(batched.elementIds, whole.elementIds);
    }
    // auto batches on llvmpipe only, and says so.
    RenderResult automatic = renderer.render(scene, camera, RenderSettings{}, diagnostics);
    const bool llvmpipe = renderer.glDescription().find("llvmpipe") != std::string::npos;
    EXPECT_EQ(automatic.stats.drawBatching.find("llvmpipe") != std::string::npos, llvmpipe)
        << automatic.stats.drawBatching;
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(Renderer, NoIdImagesUnlessAskedFor) {
    Scene scene;
    scene.setCurves(horizontalStrands("/a", 7, {0.0f}));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderResult result = renderer.render(scene, squareCamera(32), RenderSettings{}, diagnostics);
    EXPECT_TRUE(result.primIds.empty());
    EXPECT_TRUE(result.elementIds.empty());
}

TEST(Renderer, AnInstancedPrimsRepairsAreReportedOnceNotPerInstance) {
    // Three instances of a prim whose widths have the wrong count: the
    // repair is the same for each, so only the first instance reports it.
    Scene scene;
    for (int instance = 0; instance < 3; ++instance) {
        CurvesPrim prim = horizontalStrands("/proto{" + std::to_string(instance) + "}", 5, {0.5f});
        prim.instanceId = instance;
        prim.primvars["widths"].interpolation = Interpolation::Vertex;
        prim.primvars["widths"].values = {0.2f, 0.2f, 0.2f};  // 3 values for 2 vertices
        scene.setCurves(prim);
    }
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    renderer.render(scene, squareCamera(32), RenderSettings{}, diagnostics);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].where, "/proto{0}.widths");
}

// A visible mesh is drawn (over the strands' background), prepared once per
// version and refine level and sent once; a hidden one is neither drawn nor
// counted; an edit prepares and sends it again.
TEST(Renderer, MeshesArePreparedAndSentOnlyWhenTheyChange) {
    Scene scene;
    scene.setCurves(horizontalStrands("/a", 1, {0.8f}));
    MeshPrim mesh;
    mesh.path = "/ground";
    mesh.primId = 4;
    mesh.subdivisionScheme = "none";
    mesh.points = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 0.5f, 0.0f}};
    mesh.faceVertexCounts = {3};
    mesh.faceVertexIndices = {0, 1, 2};
    MeshPrim hidden = mesh;
    hidden.path = "/hidden";
    hidden.visible = false;
    scene.setMesh(mesh);
    scene.setMesh(hidden);
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    const CameraView camera = squareCamera(32);
    RenderResult first = renderer.render(scene, camera, RenderSettings{}, diagnostics, RenderOutputs{true});
    EXPECT_EQ(first.stats.preparedMeshes, 2u);
    EXPECT_EQ(first.stats.meshTriangles, 1u);
    EXPECT_TRUE(first.plan.isEnabled("meshes"));
    EXPECT_EQ(first.plan.graph().find("meshUpload")->reason,
              "1 mesh(es), 1 triangles to the GPU: a mesh changed since "
              "the last frame");
    const size_t centre = size_t(pixelRow(camera, -0.5f)) * 32 + 16;
    EXPECT_EQ(first.primIds[centre], 4);
    EXPECT_EQ(first.elementIds[centre], 0);
    EXPECT_EQ(first.color.pixels[4 * centre + 3], 1.0f);

    RenderResult second = renderer.render(scene, camera, RenderSettings{}, diagnostics, RenderOutputs{true});
    EXPECT_EQ(second.stats.preparedMeshes, 0u);
    EXPECT_EQ(second.plan.graph().find("meshUpload")->reason, "the meshes on the GPU are current: nothing to send");
    EXPECT_EQ(second.color.pixels, first.color.pixels);

    mesh.points[2].y = -0.2f;  // the triangle no longer covers y = -0.1
    scene.setMesh(mesh);
    RenderResult third = renderer.render(scene, camera, RenderSettings{}, diagnostics, RenderOutputs{true});
    EXPECT_EQ(third.stats.preparedMeshes, 1u);
    EXPECT_EQ(third.primIds[size_t(pixelRow(camera, -0.1f)) * 32 + 16], -1);
    EXPECT_EQ(first.primIds[size_t(pixelRow(camera, -0.1f)) * 32 + 16], 4);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

// Frames after the first send only what changed (per-prim GPU ranges), and
// what they draw is what a renderer that sent everything afresh draws, also
// after prims grew, vanished and came back (holes and a repack).
TEST(Renderer, LaterFramesSendOnlyChangedPrimsAndDrawTheSame) {
    Diagnostics diagnostics;
    CameraView camera = squareCamera(96);
    RenderSettings settings;
    settings.set("transparency", "binSorted");
    auto renderFresh = [&](const Scene& scene) {
        Renderer fresh(gl::defaultGlBackend());
        return fresh.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    };
    auto expectSameAsFresh = [&](const RenderResult& cached, const Scene& scene, const char* step) {
        RenderResult expected = renderFresh(scene);
        EXPECT_EQ(cached.color.pixels, expected.color.pixels) << step;
        EXPECT_EQ(cached.depth.pixels, expected.depth.pixels) << step;
        EXPECT_EQ(cached.primIds, expected.primIds) << step;
        EXPECT_EQ(cached.elementIds, expected.elementIds) << step;
    };

    Scene scene;
    scene.setCurves(horizontalStrands("/a", 1, {-0.8f, -0.4f}));
    scene.setCurves(horizontalStrands("/b", 2, {0.0f}));
    scene.setCurves(horizontalStrands("/c", 3, {0.4f, 0.8f}));
    Renderer renderer(gl::defaultGlBackend());
    RenderResult first = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    EXPECT_EQ(first.stats.preparedPrims, 3u);
    EXPECT_EQ(first.stats.uploadedSegments, 5u);

    RenderResult again = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    EXPECT_EQ(again.stats.preparedPrims, 0u);
    EXPECT_EQ(again.stats.uploadedSegments, 0u);
    EXPECT_EQ(again.color.pixels, first.color.pixels);

    // Setting a prim again unchanged is no change at all.
    scene.setCurves(horizontalStrands("/b", 2, {0.0f}));
    EXPECT_EQ(renderer.render(scene, camera, settings, diagnostics).stats.uploadedSegments, 0u);

    // /b moves: its one segment alone is sent, in place.
    scene.setCurves(horizontalStrands("/b", 2, {0.2f}));
    RenderResult moved = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    EXPECT_EQ(moved.stats.preparedPrims, 1u);
    EXPECT_EQ(moved.stats.uploadedSegments, 1u);
    expectSameAsFresh(moved, scene, "after moving /b");

    // /a grows a curve (a new range at the end), /c vanishes (a hole).
    scene.setCurves(horizontalStrands("/a", 1, {-0.8f, -0.6f, -0.4f}));
    scene.remove("/c");
    RenderResult reshaped = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
    EXPECT_EQ(reshaped.stats.uploadedSegments, 3u);
    expectSameAsFresh(reshaped, scene, "after growing /a and removing /c");

    // The same through the other transparency paths, which draw ranges
    // rather than a sorted order.
    for (const char* path : {"opaque", "unsorted", "exact"}) {
        settings.set("transparency", path);
        expectSameAsFresh(renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true}), scene, path);
    }
    EXPECT_TRUE(diagnostics.warnings().empty());
}

// The display transform on the GPU (the displayTransform pass, OCIO's GLSL)
// gives the CPU's pixels within 1e-3 (a quarter of an 8-bit step), for every
// view of hdHair's config and the plain sRGB mode, straight and over black.
TEST(Renderer, GpuDisplayTransformMatchesTheCpuOne) {
    Diagnostics diagnostics;
    Scene scene;
    CurvesPrim strands = horizontalStrands("/a", 1, {-0.6f, 0.0f, 0.6f});
    // Colours from dark to beyond 1, and a translucent strand (alpha 0.5).
    Primvar color;
    color.name = "displayColor";
    color.tupleSize = 3;
    color.interpolation = Interpolation::Uniform;
    color.interpolationAuthored = true;
    color.values = {0.02f, 0.18f, 0.9f, 1.0f, 0.5f, 0.1f, 4.0f, 2.0f, 0.3f};
    strands.primvars["displayColor"] = color;
    Primvar opacity;
    opacity.name = "displayOpacity";
    opacity.interpolation = Interpolation::Uniform;
    opacity.interpolationAuthored = true;
    opacity.values = {1.0f, 0.5f, 1.0f};
    strands.primvars["displayOpacity"] = opacity;
    scene.setCurves(strands);
    Renderer renderer(gl::defaultGlBackend());
    RenderSettings settings;
    settings.set("shadingModel", "flat");
    const CameraView camera = squareCamera(48);

    std::vector<DisplayTransform> transforms{DisplayTransform::create({})};
    for (const char* view : {"sRGB", "ACES 1.0 SDR-video", "Raw"}) {
        DisplayTransformOptions options;
        options.mode = ColorCorrectionMode::OpenColorIO;
        options.config = HDHAIR_OCIO_CONFIG;
        options.view = view;
        transforms.push_back(DisplayTransform::create(options));
    }
    for (const DisplayTransform& transform : transforms) {
        const DisplayShader shader = transform.shader();
        for (bool overBlack : {false, true}) {
            RenderOutputs outputs;
            outputs.gpuDisplay = &shader;
            outputs.displayOverBlack = overBlack;
            RenderResult result = renderer.render(scene, camera, settings, diagnostics, outputs);
            ASSERT_TRUE(result.plan.isEnabled("displayTransform"));
            const Image cpu = displayImage(result.color, transform, overBlack);
            ASSERT_EQ(result.display.pixels.size(), cpu.pixels.size());
            double largest = 0.0;
            for (size_t i = 0; i < cpu.pixels.size(); ++i)
                largest = std::max(largest, double(std::abs(result.display.pixels[i] - cpu.pixels[i])));
            EXPECT_LT(largest, 1e-3) << transform.summary() << (overBlack ? ", over black" : "");
        }
    }
    RenderResult plain = renderer.render(scene, camera, settings, diagnostics);
    EXPECT_FALSE(plain.plan.isEnabled("displayTransform"));
    EXPECT_TRUE(plain.display.pixels.empty());
}

// supersampling=N is the frame rendered N times as wide and high and
// box-filtered (bit for bit what a caller doing that by hand gets), at the
// output's size, and it changes the picture: thin strands' edges are
// antialiased rather than snapped to pixels.
TEST(Renderer, SupersamplingBoxFiltersAFrameNTimesAsLarge) {
    Scene scene;
    // 0.07 units is 1.4 px at 48 px: strand edges fall inside pixels.
    CurvesPrim strands = horizontalStrands("/a", 3, {-0.53f, 0.11f, 0.62f});
    strands.primvars["widths"].values = {0.07f};
    scene.setCurves(strands);
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    RenderSettings plain;
    plain.set("shadingModel", "flat");
    RenderSettings supersampled = plain;
    supersampled.set("supersampling", "2");
    const CameraView camera = squareCamera(48);
    CameraView fine = camera;
    fine.imageWidth = fine.imageHeight = 96;

    const RenderResult resolved = renderer.render(scene, camera, supersampled, diagnostics);
    const RenderResult byHand = renderer.render(scene, fine, plain, diagnostics);
    const RenderResult single = renderer.render(scene, camera, plain, diagnostics);
    EXPECT_EQ(resolved.color.width, 48);
    EXPECT_EQ(resolved.color.height, 48);
    EXPECT_EQ(resolved.color.pixels, boxDownsample(byHand.color, 2).pixels);
    EXPECT_NE(resolved.color.pixels, single.color.pixels);
    EXPECT_EQ(resolved.stats.imageWidth, 48);
    EXPECT_EQ(resolved.stats.supersampling, 2);
    EXPECT_EQ(resolved.stats.toJson()["supersampling"], 2);
    EXPECT_EQ(resolved.stats.settingOrigins["supersampling"]["source"], "explicit");
    EXPECT_TRUE(diagnostics.warnings().empty());
}

// Depth and ids of a supersampled frame are those of each pixel's nearest
// sample (SupersampleResolve.h): real values some fragment had, the same
// fragment for depth and ids, and a strand covering any sample of a pixel
// names it.
TEST(Renderer, SupersampledDepthAndIdsAreThoseOfThePixelsNearestSample) {
    Scene scene;
    CurvesPrim near = horizontalStrands("/near", 5, {0.3f});
    for (glm::vec3& point : near.points) point.z = 0.5f;  // nearer the camera at z = 5
    near.primvars["widths"].values = {0.03f};               // 0.6 px at 48 px: under half a pixel
    scene.setCurves(near);
    scene.setCurves(horizontalStrands("/far", 8, {0.28f}));  // wide, behind it
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("transparency", "opaque");
    settings.set("supersampling", "4");
    const CameraView camera = squareCamera(48);
    RenderOutputs outputs;
    outputs.ids = true;
    const RenderResult result = renderer.render(scene, camera, settings, diagnostics, outputs);
    settings.set("supersampling", "1");
    const RenderResult fine = renderer.render(scene, supersampledCamera(camera, 4), settings, diagnostics, outputs);
    ASSERT_EQ(result.depth.width, 48);
    ASSERT_EQ(result.primIds.size(), size_t(48 * 48));
    int nearPixels = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
            float nearest = 1.0f;
            int32_t prim = -1;
            for (int sy = 4 * y; sy < 4 * y + 4; ++sy)
                for (int sx = 4 * x; sx < 4 * x + 4; ++sx)
                    if (fine.depth.at(sx, sy, 0) < nearest) {
                        nearest = fine.depth.at(sx, sy, 0);
                        prim = fine.primIds[size_t(sy) * 192 + size_t(sx)];
                    }
            ASSERT_EQ(result.depth.at(x, y, 0), nearest) << x << "," << y;
            ASSERT_EQ(result.primIds[size_t(y) * 48 + size_t(x)], prim) << x << "," << y;
            nearPixels += prim == 5 ? 1 : 0;
        }
    // The thin near strand is named along its whole row though it covers
    // under half of each pixel, in front of the far one.
    const int row = pixelRow(camera, 0.3f);
    EXPECT_EQ(result.primIds[size_t(row) * 48 + 24], 5);
    EXPECT_GE(nearPixels, 36);
    // Without depth asked for, there is none, and the ids are the same.
    outputs.depth = false;
    settings.set("supersampling", "4");
    const RenderResult noDepth = renderer.render(scene, camera, settings, diagnostics, outputs);
    EXPECT_TRUE(noDepth.depth.pixels.empty());
    EXPECT_EQ(noDepth.primIds, result.primIds);
}

TEST(Renderer, SupersamplingRefusesTheGpuDisplayTransformAndOversizedFrames) {
    Scene scene;
    scene.setCurves(horizontalStrands("/a", 1, {0.0f}));
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("supersampling", "2");
    const DisplayShader shader = DisplayTransform::create({}).shader();
    RenderOutputs outputs;
    outputs.gpuDisplay = &shader;
    try {
        renderer.render(scene, squareCamera(16), settings, diagnostics, outputs);
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "supersampling=2 needs the display transform on the CPU (--displayTransformOn cpu): "
                                   "it must follow the box filter");
    }
    settings.set("supersampling", "8");
    try {
        renderer.render(scene, squareCamera(4000), settings, diagnostics);
        ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "supersampling=8 needs a 32000x32000 frame, larger than 16384 pixels across");
    }
}

// exactOverflow=fail: a frame whose fragments do not fit exactMemoryMB fails
// with the memory it needed instead of quietly becoming binSorted, and the
// renderer draws the next frame as if it had not happened.
TEST(Renderer, ExactTransparencyFailsInsteadOfFallingBackWhenAsked) {
    Scene scene;
    // 64 strands over one another, 0.3 opaque: about 1.1 million fragments
    // at 512 px, over the 524,288 nodes of 16 MB.
    CurvesPrim strands = horizontalStrands("/a", 1, std::vector<float>(64, 0.0f));
    Primvar opacity;
    opacity.name = "displayOpacity";
    opacity.values = {0.3f};
    strands.primvars["displayOpacity"] = opacity;
    scene.setCurves(strands);
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("transparency", "exact");
    settings.set("exactMemoryMB", "16");
    const CameraView camera = squareCamera(512);
    renderer.render(scene, squareCamera(8), RenderSettings{}, diagnostics);  // the machine's warnings, if any
    const size_t before = diagnostics.warningCount();
    const RenderResult fellBack = renderer.render(scene, camera, settings, diagnostics);
    EXPECT_FALSE(fellBack.stats.fallback.empty());
    ASSERT_EQ(diagnostics.warningCount(), before + 1);
    settings.set("exactOverflow", "fail");
    try {
        renderer.render(scene, camera, settings, diagnostics);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& error) {
        const std::string what = error.what();
        EXPECT_EQ(what.rfind("exact transparency needs ", 0), 0u) << what;
        EXPECT_NE(what.find("more than exactMemoryMB=16 (exactOverflow=fail: raise exactMemoryMB or lower "
                            "supersampling)"),
                  std::string::npos)
            << what;
    }
    EXPECT_EQ(diagnostics.warningCount(), before + 1);  // failing is not also a fallback warning
    settings.set("exactOverflow", "fallBack");
    EXPECT_EQ(renderer.render(scene, camera, settings, diagnostics).color.pixels, fellBack.color.pixels);
    settings.set("exactMemoryMB", "512");
    settings.set("exactOverflow", "fail");
    EXPECT_TRUE(renderer.render(scene, camera, settings, diagnostics).stats.fallback.empty());
}

// The software-renderer warning (hdHair/gl/SoftwareRenderer.h) reaches the
// first frame's diagnostics, once, exactly when the context is on a software
// renderer while this machine has a GPU: on the CPU-only CI machine, never.
TEST(Renderer, ReportsASoftwareRendererBesideAGpuOnceAndOtherwiseNothing) {
    const gl::testsupport::MachineGpu gpu = gl::testsupport::probeMachineGpu();
    Scene scene;
    scene.setCurves(horizontalStrands("/a", 1, {0.0f}));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    const CameraView camera = squareCamera(32);
    RenderResult first = renderer.render(scene, camera, RenderSettings{}, diagnostics);
    renderer.render(scene, camera, RenderSettings{}, diagnostics);
    size_t glWarnings = 0;
    for (const Diagnostic& warning : diagnostics.warnings()) glWarnings += warning.where == "gl" ? 1 : 0;
    const bool expected = gpu.present() && gl::isSoftwareRenderer(renderer.glDescription());
    EXPECT_EQ(glWarnings, expected ? 1u : 0u) << renderer.glDescription() << " on " << renderer.glDevice();
    EXPECT_EQ(first.stats.glDevice, renderer.glDevice());
    EXPECT_FALSE(renderer.glDevice().empty());
}
