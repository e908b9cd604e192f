// Meshes drawn as opaque occluders, on scenes built in code whose pixels
// follow by hand or from renders without the parts a mesh must hide: hair
// behind a sphere is hidden in every transparency mode, depth and ids name
// the mesh where it is nearest, colours at every interpolation land on the
// pixels they belong to, lighting follows Lambert in USD's light units,
// holes leave holes and creases keep edges sharp.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "HorizontalStrands.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/meshes/tests/TestMeshes.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using hdhair::test::cube;
using hdhair::test::quadGrid;
using hdhair::test::uvSphere;
using hdhair::test::warningsText;
using namespace hdhair::testenv;

namespace {

constexpr int kPixels = 64;
// The transparency paths, and the compute rasteriser (over binSorted).
const std::vector<const char*> kModes = {"binSorted", "exact", "unsorted", "opaque", "compute"};

// The setting that selects `mode`.
std::string modeSetting(const std::string& mode) {
    return mode == "compute" ? "strandRaster=compute" : "transparency=" + mode;
}

// Strands across the whole view at heights `ys` (HorizontalStrands.h).
CurvesPrim strands(const std::string& path, int primId, float z, const std::vector<double>& ys, float width,
                   glm::vec3 color, float opacity) {
    return horizontalStrands(path, primId, 0, z, ys, width, color, opacity);
}

MeshPrim withColor(MeshPrim mesh, glm::vec3 color) {
    mesh.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Constant, 3, {color.r, color.g, color.b});
    return mesh;
}

// An n x n grid of unit quads (faces numbered from the bottom left, row by
// row) centred on the origin at depth z, facing the camera.
MeshPrim centredGrid(int n, const std::string& path, double z = 0.0, const char* scheme = "none",
                     int refineLevel = -1) {
    MeshPrim grid = quadGrid(n, path);
    grid.subdivisionScheme = scheme;
    grid.refineLevel = refineLevel;
    grid.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(-0.5 * n, -0.5 * n, z));
    return grid;
}

RenderResult render(const Scene& scene, const CameraView& camera, const std::vector<std::string>& settings,
                    Diagnostics& diagnostics) {
    RenderSettings renderSettings;
    renderSettings.set("shadingModel", "flat");
    for (const std::string& assignment : settings) renderSettings.setFromAssignment(assignment);
    return sharedRenderer().render(scene, camera, renderSettings, diagnostics, RenderOutputs{true});
}

RenderResult render(const Scene& scene, const CameraView& camera, const std::vector<std::string>& settings = {}) {
    Diagnostics diagnostics;
    RenderResult result = render(scene, camera, settings, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    return result;
}

size_t pixelIndex(int x, int y) { return size_t(y) * kPixels + size_t(x); }

// The pixel the world point (x, y) falls in.
glm::ivec2 pixelAt(const CameraView& camera, double x, double y) {
    const glm::dvec3 p = camera.worldToPixel(glm::dvec3(x, y, 0.0));
    return glm::ivec2(int(std::floor(p.x)), int(std::floor(p.y)));
}

}  // namespace

// A head-like sphere in front of strands, a half-opaque strand and a faint
// one in front of the sphere. Where the sphere covers a pixel, the frame is
// exactly the frame of the sphere and the strands in front of it alone;
// elsewhere exactly the frame of the strands alone: colour, depth and ids,
// in every transparency mode.
TEST(MeshRendering, ASphereHidesExactlyTheStrandsBehindIt) {
    const CameraView camera = orthographicView(3.0, kPixels);
    const MeshPrim sphere = withColor(uvSphere("/head", {0.0f, 0.0f, 1.0f}, 0.8f), {0.1f, 0.8f, 0.2f});
    const CurvesPrim behind = strands("/behind", 1, 0.0f, {-0.9f, -0.5f, -0.1f, 0.3f, 0.7f, 1.1f}, 0.1f, {1, 0, 0}, 0.6f);
    const CurvesPrim front = strands("/front", 2, 2.5f, {0.45f}, 0.1f, {0, 0, 1}, 0.5f);
    const CurvesPrim faint = strands("/faint", 3, 2.5f, {-0.25f}, 0.1f, {1, 1, 1}, 0.05f);
    Scene all, sphereAndFront, strandsOnly, sphereOnly;
    for (Scene* scene : {&all, &sphereAndFront, &sphereOnly}) scene->setMesh(sphere);
    for (Scene* scene : {&all, &strandsOnly}) scene->setCurves(behind);
    for (Scene* scene : {&all, &sphereAndFront, &strandsOnly}) {
        scene->setCurves(front);
        scene->setCurves(faint);
    }
    const RenderResult covered = render(sphereOnly, camera);
    for (const char* mode : kModes) {
        const std::vector<std::string> settings{modeSetting(mode)};
        const RenderResult frame = render(all, camera, settings);
        const RenderResult expectedOnSphere = render(sphereAndFront, camera, settings);
        const RenderResult expectedElsewhere = render(strandsOnly, camera, settings);
        if (std::string(mode) == "compute")
            ASSERT_EQ(frame.stats.strandRaster, "compute");
        else
            ASSERT_EQ(frame.stats.transparency, mode);
        EXPECT_TRUE(frame.plan.isEnabled("meshes"));
        size_t sphereCount = 0, hiddenStrandPixels = 0;
        for (int y = 0; y < kPixels; ++y) {
            for (int x = 0; x < kPixels; ++x) {
                const size_t i = pixelIndex(x, y);
                const bool onSphere = covered.color.pixels[4 * i + 3] == 1.0f;
                const RenderResult& expected = onSphere ? expectedOnSphere : expectedElsewhere;
                sphereCount += onSphere;
                hiddenStrandPixels += onSphere && expectedElsewhere.primIds[i] == 1;
                for (int c = 0; c < 4; ++c)
                    ASSERT_EQ(frame.color.pixels[4 * i + size_t(c)], expected.color.pixels[4 * i + size_t(c)])
                        << mode << " pixel (" << x << ", " << y << ") channel " << c << (onSphere ? " on" : " off")
                        << " the sphere";
                ASSERT_EQ(frame.depth.pixels[i], expected.depth.pixels[i]) << mode << " (" << x << ", " << y << ")";
                ASSERT_EQ(frame.primIds[i], expected.primIds[i]) << mode << " (" << x << ", " << y << ")";
                ASSERT_EQ(frame.elementIds[i], expected.elementIds[i]) << mode << " (" << x << ", " << y << ")";
            }
        }
        // The sphere (radius 0.8 of 3 units across 64 px) covers about
        // pi (0.8 * 64 / 3)^2 = 915 pixels (its 32-gon a little less), and
        // hides strands on some.
        EXPECT_NEAR(double(sphereCount), 915.0, 30.0) << mode;
        EXPECT_GT(hiddenStrandPixels, 100u) << mode;
    }
}

// A flat quad at z = 2 in front of an opaque strand at z = 0, a half-opaque
// strand at z = 3 and a faint (0.05) one at z = 3, seen orthographically
// from z = 10 with clipping range [0.1, 100]: window depth (d - 0.1) / 99.9
// at distance d. Where the mesh is nearest (or only faint hair is in front
// of it), depth and ids are the mesh's: primId, instanceId, the face.
TEST(MeshRendering, DepthAndIdsAreTheMeshsWhereItIsNearest) {
    const CameraView camera = orthographicView(4.0, kPixels);
    MeshPrim quads = withColor(centredGrid(2, "/quads", 2.0), {0.5f, 0.5f, 0.5f});  // (-1, -1) to (1, 1): 4 faces
    quads.primId = 40;
    quads.instanceId = 3;
    Scene scene;
    scene.setMesh(quads);
    scene.setCurves(strands("/behind", 1, 0.0f, {-0.5f}, 0.25f, {1, 0, 0}, 1.0f));
    scene.setCurves(strands("/front", 2, 3.0f, {0.5f}, 0.25f, {0, 0, 1}, 0.5f));
    scene.setCurves(strands("/faint", 3, 3.0f, {0.0f}, 0.25f, {1, 1, 1}, 0.05f));
    const float meshDepth = float((8.0 - 0.1) / 99.9), frontDepth = float((7.0 - 0.1) / 99.9);
    for (const char* mode : kModes) {
        const RenderResult frame = render(scene, camera, {modeSetting(mode)});
        auto expectPixel = [&](double x, double y, float depth, int primId, int instanceId, int elementId) {
            const glm::ivec2 p = pixelAt(camera, x, y);
            const size_t i = pixelIndex(p.x, p.y);
            const std::string where = std::string(mode) + " at (" + std::to_string(x) + ", " + std::to_string(y) + ")";
            EXPECT_NEAR(frame.depth.pixels[i], depth, 1e-6f) << where;
            EXPECT_EQ(frame.primIds[i], primId) << where;
            EXPECT_EQ(frame.instanceIds[i], instanceId) << where;
            EXPECT_EQ(frame.elementIds[i], elementId) << where;
        };
        expectPixel(-0.5, -0.5, meshDepth, 40, 3, 0);  // the opaque strand behind: hidden
        expectPixel(0.5, -0.5, meshDepth, 40, 3, 1);
        expectPixel(-0.5, 0.25, meshDepth, 40, 3, 2);
        expectPixel(0.5, 0.25, meshDepth, 40, 3, 3);
        expectPixel(0.5, 0.5, frontDepth, 2, 0, 0);
        // The faint strand: looked through under blending, solid when opaque.
        if (std::string(mode) == "opaque")
            expectPixel(-0.5, 0.05, frontDepth, 3, 0, 0);
        else
            expectPixel(-0.5, 0.05, meshDepth, 40, 3, 2);
        expectPixel(1.5, -0.5, float((10.0 - 0.1) / 99.9), 1, 0, 0);  // off the mesh: the strand behind
        expectPixel(1.5, 1.5, 1.0f, -1, -1, -1);
        // Colour over the mesh: the half-opaque blue strand over grey.
        const glm::ivec2 p = pixelAt(camera, 0.5, 0.5);
        const float* rgba = &frame.color.pixels[4 * pixelIndex(p.x, p.y)];
        if (std::string(mode) != "opaque") {
            EXPECT_NEAR(rgba[0], 0.25f, 1e-5f) << mode;
            EXPECT_NEAR(rgba[2], 0.75f, 1e-5f) << mode;
            EXPECT_NEAR(rgba[3], 1.0f, 1e-6f) << mode;
        }
    }
}

// Flat shading on a 2 x 2 grid of unit quads facing the camera: uniform,
// faceVarying and vertex colours at pixel centres, where vertex colours
// linear in x interpolate to the centre's x exactly.
TEST(MeshRendering, ColoursAtEveryInterpolationLandOnTheirPixels) {
    const CameraView camera = orthographicView(4.0, kPixels);
    MeshPrim grid = centredGrid(2, "/grid");
    const std::vector<glm::vec3> faceColors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
    auto centreColor = [&](const Scene& scene, double x, double y) {
        const RenderResult frame = render(scene, camera);
        const glm::ivec2 p = pixelAt(camera, x, y);
        const float* rgba = &frame.color.pixels[4 * pixelIndex(p.x, p.y)];
        return glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3]);
    };
    const double quadrants[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};

    std::vector<float> uniform;
    for (const glm::vec3& c : faceColors) uniform.insert(uniform.end(), {c.r, c.g, c.b});
    grid.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Uniform, 3, uniform);
    Scene scene;
    scene.setMesh(grid);
    for (int f = 0; f < 4; ++f)
        EXPECT_EQ(centreColor(scene, quadrants[f][0], quadrants[f][1]), glm::vec4(faceColors[size_t(f)], 1.0f));

    // FaceVarying, indexed: every corner of face f names value f.
    Primvar faceVarying = authoredPrimvar("displayColor", Interpolation::FaceVarying, 3, uniform);
    for (int f = 0; f < 4; ++f) faceVarying.indices.insert(faceVarying.indices.end(), 4, f);
    grid.primvars["displayColor"] = faceVarying;
    scene.setMesh(grid);
    for (int f = 0; f < 4; ++f)
        EXPECT_EQ(centreColor(scene, quadrants[f][0], quadrants[f][1]), glm::vec4(faceColors[size_t(f)], 1.0f));

    // Vertex: red = x / 2 in the grid's own coordinates (0 to 2).
    std::vector<float> vertex;
    for (const glm::vec3& point : grid.points) vertex.insert(vertex.end(), {point.x / 2.0f, 0.0f, 1.0f});
    grid.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Vertex, 3, vertex);
    scene.setMesh(grid);
    for (double x : {-0.7, -0.2, 0.4, 0.9}) {
        const glm::ivec2 p = pixelAt(camera, x, 0.3);
        const double centreX = -2.0 + (p.x + 0.5) * 4.0 / kPixels;  // 4 units across 64 pixels
        EXPECT_NEAR(centreColor(scene, x, 0.3).r, float((centreX + 1.0) / 2.0), 1e-5f) << x;
    }
}

// Lambert in USD's units: a DistantLight of intensity pi head-on on an
// albedo gives radiance albedo / pi * pi * cos = albedo; tilted 60 degrees,
// half of it. The hair convention is the same (Kajiya-Kay's Kd / pi).
TEST(MeshRendering, LambertUnderADistantLight) {
    const CameraView camera = orthographicView(4.0, kPixels);
    const glm::vec3 albedo(0.5f, 0.25f, 1.0f);
    const MeshPrim grid = withColor(centredGrid(2, "/grid"), albedo);
    for (double tilt : {0.0, 60.0}) {
        Scene scene;
        scene.setMesh(grid);
        LightPrim light;
        light.path = "/sun";
        light.type = LightType::Distant;
        light.intensity = glm::pi<float>();
        light.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(tilt), glm::dvec3(1.0, 0.0, 0.0));
        scene.setLight(light);
        const RenderResult frame = render(scene, camera, {"shadingModel=kajiyaKay"});
        EXPECT_TRUE(frame.plan.recipe().lighting.meshesLit);
        const float* rgba = &frame.color.pixels[4 * pixelIndex(kPixels / 2, kPixels / 2)];
        const float cosine = float(std::cos(glm::radians(tilt)));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgba[c], albedo[c] * cosine, 1e-5f) << "tilt " << tilt;
        EXPECT_EQ(rgba[3], 1.0f);
    }
}

// catmullClark at level 2 on a 4 x 4 grid with interior face 5 a hole: its
// centre shows nothing, its neighbours' centres are covered.
TEST(MeshRendering, HolesLeaveHoles) {
    const CameraView camera = orthographicView(4.0, kPixels);
    MeshPrim grid = withColor(centredGrid(4, "/grid", 0.0, "catmullClark", 2), {1, 1, 1});
    grid.holeIndices = {5};  // column 1, row 1: the square (-1, -1) to (0, 0)
    Scene scene;
    scene.setMesh(grid);
    const RenderResult frame = render(scene, camera);
    auto alphaAt = [&](double x, double y) {
        const glm::ivec2 p = pixelAt(camera, x, y);
        return frame.color.pixels[4 * pixelIndex(p.x, p.y) + 3];
    };
    EXPECT_EQ(alphaAt(-0.5, -0.5), 0.0f);
    EXPECT_EQ(alphaAt(0.5, -0.5), 1.0f);
    EXPECT_EQ(alphaAt(-0.5, 0.5), 1.0f);
    EXPECT_EQ(alphaAt(-1.5, -0.5), 1.0f);
    EXPECT_EQ(alphaAt(-0.5, -1.5), 1.0f);
}

// A cube seen face on: with every edge infinitely sharp its silhouette is
// the square [-1, 1]^2; smooth (Catmull-Clark's limit, a rounded box of
// radius 0.84 to 0.87) the corner region near (0.95, 0.95) is empty.
TEST(MeshRendering, SharpCreasesKeepTheCubesCorners) {
    const CameraView camera = orthographicView(3.0, kPixels);
    MeshPrim smooth = withColor(cube("/box"), {1, 1, 1});
    smooth.refineLevel = 3;
    MeshPrim creased = smooth;
    const std::vector<int> edges = {0, 1, 1, 3, 3, 2, 2, 0, 4, 5, 5, 7, 7, 6, 6, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    creased.creaseIndices = edges;
    creased.creaseLengths.assign(12, 2);
    creased.creaseSharpnesses.assign(12, 10.0f);
    auto alphaNearCorner = [&](const MeshPrim& mesh) {
        Scene scene;
        scene.setMesh(mesh);
        const RenderResult frame = render(scene, camera);
        const glm::ivec2 p = pixelAt(camera, 0.95, 0.95);
        return frame.color.pixels[4 * pixelIndex(p.x, p.y) + 3];
    };
    EXPECT_EQ(alphaNearCorner(creased), 1.0f);
    EXPECT_EQ(alphaNearCorner(smooth), 0.0f);
}

// The opaque path multisampled: the mesh's edges are averaged over the
// samples (some edge pixel partly covered) while its inside and the hair
// hidden behind it are as without multisampling.
TEST(MeshRendering, MultisampledOpaqueFramesAntialiasMeshEdges) {
    const CameraView camera = orthographicView(3.0, kPixels);
    Scene scene;
    MeshPrim sphere = withColor(uvSphere("/head", {0.0f, 0.0f, 1.0f}, 0.8f), {0.1f, 0.8f, 0.2f});
    sphere.primId = 7;
    scene.setMesh(sphere);
    scene.setCurves(strands("/behind", 1, 0.0f, {0.0f}, 0.2f, {1, 0, 0}, 1.0f));
    const RenderResult plain = render(scene, camera, {"transparency=opaque"});
    const RenderResult multisampled = render(scene, camera, {"transparency=opaque", "msaaSamples=4"});
    ASSERT_TRUE(multisampled.plan.isEnabled("resolve"));
    const size_t centre = pixelIndex(kPixels / 2, kPixels / 2);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(multisampled.color.pixels[4 * centre + size_t(c)], plain.color.pixels[4 * centre + size_t(c)]);
    EXPECT_EQ(multisampled.primIds[centre], 7);  // the strand behind is hidden
    size_t partial = 0;
    for (size_t i = 0; i < size_t(kPixels * kPixels); ++i) {
        const float alpha = multisampled.color.pixels[4 * i + 3];
        partial += alpha > 0.0f && alpha < 1.0f;
    }
    EXPECT_GT(partial, 20u);
}

// Lit meshes in every light batch: five lights one at a time give the image
// of all five at once, within 1/255, with hair over the mesh, in every mode.
TEST(MeshRendering, LightBatchesSumTheMeshesColours) {
    const CameraView camera = orthographicView(3.0, kPixels);
    Scene scene;
    scene.setMesh(withColor(uvSphere("/head", {0.0f, 0.0f, 1.0f}, 0.8f), {0.6f, 0.5f, 0.4f}));
    scene.setCurves(strands("/front", 2, 2.5f, {0.1f, 0.4f}, 0.1f, {0.3f, 0.2f, 0.1f}, 0.5f));
    for (int i = 0; i < 5; ++i) {
        LightPrim light;
        light.path = "/light" + std::to_string(i);
        light.intensity = 0.5f;
        light.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(20.0 * i - 40.0), glm::dvec3(0.0, 1.0, 0.0));
        scene.setLight(light);
    }
    for (const char* mode : kModes) {
        const std::string transparency = modeSetting(mode);
        const RenderResult together = render(scene, camera, {transparency, "shadingModel=kajiyaKay", "lightsPerPass=16"});
        const RenderResult batched = render(scene, camera, {transparency, "shadingModel=kajiyaKay", "lightsPerPass=1"});
        EXPECT_EQ(batched.stats.lightPasses, 5u);
        EXPECT_TRUE(batched.plan.isEnabled("lightBatch 5"));
        float largest = 0.0f;
        for (size_t i = 0; i < together.color.pixels.size(); ++i)
            largest = std::max(largest, std::abs(together.color.pixels[i] - batched.color.pixels[i]));
        EXPECT_LE(largest, 1.0f / 255.0f) << mode;
        EXPECT_GT(together.color.pixels[4 * pixelIndex(kPixels / 2, kPixels / 2)], 0.05f) << mode << ": lit";
    }
}

// Unlit meshes (shadingModel=flat) next to lit hair: their colour is counted
// once however many light batches the hair takes.
TEST(MeshRendering, UnlitMeshesAreCountedOnceAcrossLightBatches) {
    const CameraView camera = orthographicView(3.0, kPixels);
    Scene scene;
    scene.setMesh(withColor(uvSphere("/head", {0.0f, 0.0f, 1.0f}, 0.8f), {0.6f, 0.5f, 0.4f}));
    CurvesPrim hair = strands("/front", 2, 2.5f, {0.9f}, 0.1f, {0.3f, 0.2f, 0.1f}, 1.0f);
    hair.shadingModel = "kajiyaKay";
    scene.setCurves(hair);
    for (int i = 0; i < 3; ++i) {
        LightPrim light;
        light.path = "/light" + std::to_string(i);
        scene.setLight(light);
    }
    const RenderResult frame = render(scene, camera, {"lightsPerPass=1"});
    EXPECT_EQ(frame.stats.lightPasses, 3u);
    EXPECT_FALSE(frame.plan.recipe().lighting.meshesLit);
    const float* rgba = &frame.color.pixels[4 * pixelIndex(kPixels / 2, kPixels / 2)];
    EXPECT_EQ(glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3]), glm::vec4(0.6f, 0.5f, 0.4f, 1.0f));
}

// Exact transparency over its memory budget redraws the frame binSorted:
// the meshes are drawn again under it.
TEST(MeshRendering, ExactFallingBackRedrawsTheMeshes) {
    // 100 faint sheets over y in [-1.5, -0.2], 128 x 55 pixels each:
    // 704,000 fragments, more than the 524,288 that 16 MB hold.
    const CameraView camera = orthographicView(3.0, 128);
    Scene scene;
    MeshPrim sphere = withColor(uvSphere("/head", {0.0f, 0.0f, 1.0f}, 0.8f), {0.1f, 0.8f, 0.2f});
    sphere.primId = 7;
    scene.setMesh(sphere);
    for (int i = 0; i < 100; ++i)
        scene.setCurves(strands("/sheet" + std::to_string(i), 100 + i, 2.0f + 0.005f * float(i), {-0.85f}, 1.3f,
                                {1, 1, 1}, 0.05f));
    Diagnostics diagnostics;
    const RenderResult frame =
        render(scene, camera, {"transparency=exact", "exactMemoryMB=16"}, diagnostics);
    ASSERT_EQ(frame.stats.transparency, "binSorted");
    const size_t centre = size_t(64) * 128 + 64;  // on the sphere, under no sheet
    EXPECT_EQ(frame.color.pixels[4 * centre + 1], 0.8f);
    EXPECT_EQ(frame.primIds[centre], 7);
    EXPECT_GE(frame.elementIds[centre], 0);
    EXPECT_NE(warningsText(diagnostics).find("rendered with binSorted (1024 bins) instead"), std::string::npos);
}

// Points that are not numbers and faces of no area: warned about, and the
// frame stays finite.
TEST(MeshRendering, BadMeshesWarnAndStayFinite) {
    const CameraView camera = orthographicView(4.0, kPixels);
    MeshPrim grid = withColor(centredGrid(3, "/grid", 0.0, "catmullClark", 2), {1, 1, 1});
    grid.points[5] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    grid.points[15] = grid.points[11];  // face 8: (2, 2) (3, 2) (3, 2) (2, 2)
    grid.points[14] = grid.points[10];
    Scene scene;
    scene.setMesh(grid);
    LightPrim light;
    light.path = "/sun";
    scene.setLight(light);
    Diagnostics diagnostics;
    const RenderResult frame = render(scene, camera, {"shadingModel=kajiyaKay"}, diagnostics);
    for (float value : frame.color.pixels) ASSERT_TRUE(std::isfinite(value));
    for (float value : frame.depth.pixels) ASSERT_TRUE(std::isfinite(value));
    EXPECT_NE(warningsText(diagnostics).find("/grid.points: 1 point is not finite"), std::string::npos)
        << warningsText(diagnostics);
    EXPECT_NE(warningsText(diagnostics).find("/grid.faceVertexCounts: 1 face has no area (first: face 8)"),
              std::string::npos)
        << warningsText(diagnostics);
}
