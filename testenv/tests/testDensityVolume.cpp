// Lights shadowed through the hair's density volume (HairDensityGrid.h,
// shaders/include/densityVolume.glsl): a sphere light inside the hair,
// which no map's view can hold, shadows a plane through a sheet of strands
// by exactly the transmittance worked out by hand, and the hard cases stay
// finite. shadowMode=auto plans the volume only for such a light.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/meshes/tests/TestMeshes.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using hdhair::test::quadGrid;
using hdhair::test::warningsText;
using namespace hdhair::testenv;

namespace {

constexpr int kPixels = 96;
constexpr double kAcross = 4.0;
constexpr double kPixel = kAcross / kPixels;

// A sheet of straight strands along x (x in [-2, 2]) at depth z, rows
// `pitch` apart over y in [-1.5, 1.5], black and flat-shaded (they add no
// light, only cover), opaque: a ray crossing the sheet at angle θ to its
// normal has optical depth (w / p) / cos θ.
CurvesPrim sheet(const std::string& path, double z, double pitch, double width) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Linear;
    prim.shadingModel = "flat";
    for (double y = -1.5 + 0.5 * pitch; y < 1.5; y += pitch) {
        prim.curveVertexCounts.push_back(2);
        prim.points.push_back({-2.0f, float(y), float(z)});
        prim.points.push_back({2.0f, float(y), float(z)});
    }
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Constant, 1, {float(width)});
    prim.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Constant, 3, {0.0f, 0.0f, 0.0f});
    return prim;
}

LightPrim sphereLightAt(glm::dvec3 position) {
    LightPrim light;
    light.path = "/light";
    light.type = LightType::Sphere;
    light.radius = 0.02f;
    light.intensity = 10.0f;
    light.worldTransform = glm::translate(glm::dmat4(1.0), position);
    return light;
}

// A grey plane at z = -0.6 facing the light at the origin; a sheet at
// z = -0.3 between them (w/p = 0.4); one strand at z = +0.3 in a corner
// puts the light inside the hair's bounds.
constexpr double kPlaneZ = -0.6, kSheetZ = -0.3, kPitch = 0.002, kWidth = 0.0008;

Scene lightInsideTheHair(glm::dvec3 light = glm::dvec3(0.0)) {
    Scene scene;
    MeshPrim plane = quadGrid(4, "/plane");
    plane.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Constant, 3, {0.5f, 0.5f, 0.5f});
    plane.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(-2.0, -2.0, kPlaneZ));
    scene.setMesh(plane);
    scene.setCurves(sheet("/sheet", kSheetZ, kPitch, kWidth));
    CurvesPrim corner = sheet("/corner", 0.3, 1.0, kWidth);
    corner.curveVertexCounts.resize(1);
    corner.points = {{1.9f, 1.45f, 0.3f}, {2.0f, 1.45f, 0.3f}};
    scene.setCurves(corner);
    scene.setLight(sphereLightAt(light));
    return scene;
}

RenderResult render(const Scene& scene, const std::vector<std::string>& settings, Diagnostics& diagnostics) {
    RenderSettings renderSettings;
    for (const std::string& assignment : settings) renderSettings.setFromAssignment(assignment);
    return sharedRenderer().render(scene, orthographicView(kAcross, kPixels), renderSettings, diagnostics);
}

// The one warning these scenes give: the light is inside the bounds of the
// hair and the plane, which no one view of the meshes holds, so the plane
// casts no shadow from it (it has nothing to shadow here).
RenderResult render(const Scene& scene, const std::vector<std::string>& settings = {}) {
    Diagnostics diagnostics;
    RenderResult result = render(scene, settings, diagnostics);
    const std::string warnings = warningsText(diagnostics);
    EXPECT_LE(diagnostics.warningCount(), 1u) << warnings;
    if (diagnostics.warningCount() == 1) {
        EXPECT_NE(warnings.find("the meshes cast no shadows from this light"), std::string::npos) << warnings;
    }
    return result;
}

// The world point on the plane at pixel (px, py)'s centre.
glm::dvec3 planeAt(int px, int py) {
    return {-0.5 * kAcross + (px + 0.5) * kPixel, 0.5 * kAcross - (py + 0.5) * kPixel, kPlaneZ};
}

// Over the plane's pixels whose ray to the light crosses the sheet well
// inside it: the largest |shadowed / unshadowed / expected - 1|, and how
// many pixels were compared. `opticalDepthScale` scales the expected depth.
std::pair<double, size_t> largestTransmittanceError(const RenderResult& shadowed, const RenderResult& unshadowed,
                                                    double opticalDepthScale = 1.0) {
    double largest = 0.0;
    size_t compared = 0;
    for (int py = 0; py < kPixels; ++py)
        for (int px = 0; px < kPixels; ++px) {
            const glm::dvec3 p = planeAt(px, py);
            if (std::abs(p.x) > 1.8 || std::abs(p.y) > 1.3) continue;
            const double cosine = -kPlaneZ / glm::length(p);
            const double expected = std::exp(-opticalDepthScale * (kWidth / kPitch) / cosine);
            const size_t i = 4 * (size_t(py) * kPixels + size_t(px));
            for (int c = 0; c < 3; ++c) {
                const double lit = unshadowed.color.pixels[i + size_t(c)];
                if (!(lit > 1e-4)) continue;
                largest = std::max(largest, std::abs(shadowed.color.pixels[i + size_t(c)] / lit / expected - 1.0));
            }
            ++compared;
        }
    return {largest, compared};
}

}  // namespace

// The plane behind the sheet gets exp(-(w/p)/cos θ) of the light the same
// frame without shadows gives it, pixel by pixel, within 2.5 % (1.3 %
// measured: the voxels hold about 15 rows of strands each, blurred over
// two by the splat and the trilinear lookup); the frame's own pixels are
// finite. Half the density, as a mutation, misses the bound everywhere.
TEST(DensityVolume, ALightInsideTheHairShadowsThroughTheVolume) {
    const Scene scene = lightInsideTheHair();
    const RenderResult shadowed = render(scene);
    const RenderResult unshadowed = render(scene, {"shadowMode=off"});
    EXPECT_TRUE(shadowed.plan.isEnabled("densityVolume"));
    EXPECT_FALSE(shadowed.plan.isEnabled("deepOpacity /light")) << "no map's view holds the hair";
    // --stats counts its memory: R32F, one float a voxel, and its mip
    // chain, each level half the last along every side, down to one voxel.
    ASSERT_TRUE(shadowed.stats.gpuBytes.count("densityVolume"));
    const glm::ivec3 dims = shadowed.plan.recipe().shadows.volumeGrid.dims;
    uint64_t voxels = 0;
    for (int level = 0; (std::max({dims.x, dims.y, dims.z}) >> level) > 0; ++level)
        voxels += uint64_t(std::max(dims.x >> level, 1)) * uint64_t(std::max(dims.y >> level, 1)) *
                  uint64_t(std::max(dims.z >> level, 1));
    EXPECT_GT(voxels, shadowed.plan.recipe().shadows.volumeGrid.voxelCount());
    EXPECT_EQ(shadowed.stats.gpuBytes.at("densityVolume"), 4u * voxels);
    // --explain says why, on the map's passes and on the volume's.
    ASSERT_TRUE(shadowed.plan.graph().find("deepOpacity /light"));
    EXPECT_NE(shadowed.plan.graph().find("deepOpacity /light")->reason.find("no map: through the hair's density volume"),
              std::string::npos)
        << shadowed.plan.graph().find("deepOpacity /light")->reason;
    EXPECT_NE(shadowed.plan.graph().find("densityVolume")->reason.find("/light: through the hair's density volume "
                                                                      "(shadowMode=auto): the light is inside"),
              std::string::npos)
        << shadowed.plan.graph().find("densityVolume")->reason;
    const auto [largest, compared] = largestTransmittanceError(shadowed, unshadowed);
    std::printf("largest |T / exp(-(w/p)/cos) - 1| over %zu pixels: %.4f\n", compared, largest);
    EXPECT_GT(compared, 5000u);
    EXPECT_LT(largest, 0.025);
    EXPECT_GT(largestTransmittanceError(shadowed, unshadowed, 0.5).first, 0.025) << "half the density must fail";
    for (float value : shadowed.color.pixels) ASSERT_TRUE(std::isfinite(value));

    // Without the volume (deepOpacity), the light shades unshadowed, and says so.
    Diagnostics diagnostics;
    const RenderResult mapsOnly = render(scene, {"shadowMode=deepOpacity"}, diagnostics);
    EXPECT_NE(warningsText(diagnostics).find("inside or too close"), std::string::npos) << warningsText(diagnostics);
    EXPECT_FALSE(mapsOnly.plan.isEnabled("densityVolume"));
    EXPECT_GT(largestTransmittanceError(mapsOnly, unshadowed).first, 0.025) << "an unshadowed light must fail";
}

// shadowMode=volume shadows a distant light through the volume too: the
// plane behind the sheet, lit straight on, gets exp(-w/p), within 2.5 %.
TEST(DensityVolume, ShadowModeVolumeShadowsEveryLight) {
    Scene scene = lightInsideTheHair();
    LightPrim distant;
    distant.path = "/light";
    distant.intensity = 2.0f;  // emits along -Z: straight at the plane
    scene.setLight(distant);
    const RenderResult shadowed = render(scene, {"shadowMode=volume"});
    const RenderResult unshadowed = render(scene, {"shadowMode=off"});
    EXPECT_TRUE(shadowed.plan.isEnabled("densityVolume"));
    EXPECT_FALSE(shadowed.plan.isEnabled("deepOpacity /light"));
    size_t compared = 0;
    for (int py = 0; py < kPixels; ++py)
        for (int px = 0; px < kPixels; ++px) {
            const glm::dvec3 p = planeAt(px, py);
            if (std::abs(p.x) > 1.8 || std::abs(p.y) > 1.3) continue;
            const size_t i = 4 * (size_t(py) * kPixels + size_t(px));
            EXPECT_NEAR(shadowed.color.pixels[i] / unshadowed.color.pixels[i], std::exp(-kWidth / kPitch), 0.025 * 0.67)
                << px << ", " << py;
            ++compared;
        }
    EXPECT_GT(compared, 5000u);
}

// A light outside the hair keeps its deep opacity map under auto: the
// volume is not built and costs nothing.
TEST(DensityVolume, AutoBuildsNoVolumeForALightOutsideTheHair) {
    const Scene scene = lightInsideTheHair(glm::dvec3(0.0, 0.0, 5.0));
    const RenderResult frame = render(scene);
    EXPECT_TRUE(frame.plan.isEnabled("deepOpacity /light"));
    EXPECT_FALSE(frame.plan.isEnabled("densityVolume"));
    EXPECT_EQ(frame.stats.gpuBytes.count("densityVolume") ? frame.stats.gpuBytes.at("densityVolume") : 0u, 4u)
        << "the 1-voxel placeholder only";
}

// Hard cases: a light exactly on a strand, zero-width strands, and a budget
// far under the grid the hair calls for (warned; coarser voxels, the same
// light: nothing lost).
TEST(DensityVolume, HardCasesStayFiniteAndBounded) {
    Scene onStrand = lightInsideTheHair(glm::dvec3(0.0, -1.5 + 0.5 * kPitch, kSheetZ));
    const RenderResult exactlyOn = render(onStrand);
    for (float value : exactlyOn.color.pixels) ASSERT_TRUE(std::isfinite(value) && value >= 0.0f);

    Scene zeroWidth = lightInsideTheHair();
    zeroWidth.setCurves(sheet("/sheet", kSheetZ, kPitch, 0.0));
    const RenderResult bare = render(zeroWidth, {"shadowMode=off"});
    const RenderResult volume = render(zeroWidth);
    for (size_t i = 0; i < volume.color.pixels.size(); ++i)
        ASSERT_NEAR(volume.color.pixels[i], bare.color.pixels[i], 1e-6f) << "zero-width strands block nothing";

    Diagnostics diagnostics;
    const Scene scene = lightInsideTheHair();
    const RenderResult coarse = render(scene, {"densityVolumeMemoryMB=1"}, diagnostics);
    EXPECT_NE(warningsText(diagnostics).find("densityVolumeMemoryMB=1 holds"), std::string::npos)
        << warningsText(diagnostics);
    const RenderResult unshadowed = render(scene, {"shadowMode=off"});
    EXPECT_LT(largestTransmittanceError(coarse, unshadowed).first, 0.1) << "coarser, not lost";
}
