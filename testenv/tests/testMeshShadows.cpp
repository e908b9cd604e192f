// Shadows between meshes and hair: a mesh hides the hair, other meshes and
// its own faces behind it from a light (its depth in the light's mesh view,
// ShadowMapPass::renderMeshDepth), and hair shadows a mesh through its deep
// opacity map (shaders/mesh.frag). Where each shadow falls follows from the
// geometry by hand, and so does how dark the hair's shadow on a mesh is:
// T = exp(-k opacity), k = 1.

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "DistantLight.h"
#include "HorizontalStrands.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/meshes/tests/TestMeshes.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using hdhair::test::quadGrid;
using hdhair::test::uvSphere;
using hdhair::test::warningsText;
using namespace hdhair::testenv;

namespace {

constexpr int kPixels = 96;
constexpr double kAcross = 4.0;                    // world units across the view
constexpr double kPixel = kAcross / kPixels;       // a pixel's world size
constexpr double kMargin = 2.0 * kPixel + 0.02;    // edges: two pixels and a texel's filter either side

RenderResult render(const Scene& scene, const std::vector<std::string>& settings = {}) {
    RenderSettings renderSettings;
    for (const std::string& assignment : settings) renderSettings.setFromAssignment(assignment);
    Diagnostics diagnostics;
    RenderResult result =
        sharedRenderer().render(scene, orthographicView(kAcross, kPixels), renderSettings, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    return result;
}

// The world point (x, y) on the plane z = 0 at pixel (px, py)'s centre.
glm::dvec2 worldAt(int px, int py) {
    return {-0.5 * kAcross + (px + 0.5) * kPixel, 0.5 * kAcross - (py + 0.5) * kPixel};
}

// How far inside (negative) or outside (positive) the shadow of a sphere
// (centre c, radius r) the point p is, for light travelling against
// `towardsLight`: the distance from c to the ray p + t towardsLight, less r
// (+infinity where the sphere is behind p).
double outsideSphereShadow(glm::dvec3 p, glm::dvec3 towardsLight, glm::dvec3 c, double r) {
    const glm::dvec3 l = glm::normalize(towardsLight);
    const double t = glm::dot(c - p, l);
    if (t <= 0.0) return std::numeric_limits<double>::infinity();
    return glm::length(c - (p + t * l)) - r;
}

MeshPrim grey(MeshPrim mesh) {
    mesh.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Constant, 3, {0.5f, 0.5f, 0.5f});
    return mesh;
}

}  // namespace

// Opaque strands in the plane z = 0, lit from +X+Z; a sphere above them
// (seen beside its shadow from the camera at +Z) casts a shadow whose
// outline follows by hand. Strand pixels well inside it are black (the only
// light is blocked; no ambient), those well outside it are exactly as
// without the sphere; the sphere has no part in the strands' own shadows.
// Looked up per fragment, "well" is two pixels and a texel's filter. Per
// tessellated point (the default) the edge is also interpolated along a
// segment, and these strands are one span 10 units long, which vertex
// shadows cut into their most, 64 segments of 0.16 (0.11 across the light's
// rays, which meet the strands at 45 degrees): outside, "well" takes that
// too; inside, where the shadow is at most 0.15 deep, the darkest strand
// pixel must be black.
class SphereShadow : public ::testing::TestWithParam<const char*> {};

TEST_P(SphereShadow, DarkensExactlyTheStrandsInItsShadow) {
    const bool perVertex = std::string(GetParam()) == "vertex";
    const double margin = kMargin + (perVertex ? 10.0 / 64.0 * std::sqrt(0.5) : 0.0);
    float darkest = 1.0f;
    const glm::dvec3 towardsLight(1.0, 0.0, 1.0);
    const glm::dvec3 centre(0.6, 0.0, 1.0);
    const double radius = 0.3;
    const std::vector<double> heights{-0.75, -0.45, -0.15, 0.15, 0.45, 0.75};
    const double width = 0.2;
    Scene strandsOnly;
    strandsOnly.setCurves(horizontalStrands("/hair", 1, 0, 0.0f, heights, width, {0.9f, 0.7f, 0.5f}, 1.0f));
    strandsOnly.setLight(distantLightFrom(towardsLight));
    Scene withSphere = strandsOnly;
    withSphere.setMesh(grey(uvSphere("/sphere", glm::vec3(centre), float(radius))));

    const std::vector<std::string> sampling{std::string("shadowSampling=") + GetParam()};
    const RenderResult bare = render(strandsOnly, sampling);
    const RenderResult shadowed = render(withSphere, sampling);
    ASSERT_TRUE(shadowed.plan.isEnabled("meshShadow /light"));
    EXPECT_FALSE(bare.plan.graph().find("meshShadow /light")) << "no meshes, no mesh shadow pass";

    size_t inside = 0, outside = 0;
    for (int py = 0; py < kPixels; ++py) {
        for (int px = 0; px < kPixels; ++px) {
            const glm::dvec2 w = worldAt(px, py);
            // The strand this pixel lies well within, if any.
            const double* strand = nullptr;
            for (const double& y : heights)
                if (std::abs(w.y - y) < 0.5 * width - kPixel) strand = &y;
            if (!strand) continue;
            // Not where the camera sees the sphere itself.
            if (glm::length(glm::dvec2(w.x - centre.x, w.y - centre.y)) < radius + kMargin) continue;
            const size_t i = 4 * (size_t(py) * kPixels + size_t(px));
            const double outsideBy = outsideSphereShadow({w.x, *strand, 0.0}, towardsLight, centre, radius);
            if (outsideBy < -kMargin) {
                ++inside;
                for (int c = 0; c < 3; ++c) {
                    darkest = std::min(darkest, shadowed.color.pixels[i + size_t(c)]);
                    if (!perVertex) {
                        ASSERT_LT(shadowed.color.pixels[i + size_t(c)], 1e-6f)
                            << "(" << px << ", " << py << ") in shadow";
                    }
                }
            } else if (outsideBy > margin) {
                ++outside;
                for (int c = 0; c < 4; ++c)
                    ASSERT_NEAR(shadowed.color.pixels[i + size_t(c)], bare.color.pixels[i + size_t(c)], 1e-6f)
                        << "(" << px << ", " << py << ") out of the shadow";
            }
            ASSERT_EQ(shadowed.color.pixels[i + 3], 1.0f) << "the strands stay opaque";
        }
    }
    // The shadow's outline is an ellipse 0.42 x 0.3 about x = -0.4: the
    // strands at y = +-0.15 cross it well inside for about 0.5 units (12
    // pixels) each, on two or three rows.
    EXPECT_GT(inside, 30u);
    EXPECT_LT(darkest, 1e-6f) << "the shadow's middle";
    EXPECT_GT(outside, 600u);
}

INSTANTIATE_TEST_SUITE_P(MeshShadows, SphereShadow, ::testing::Values("fragment", "vertex"));

// Opaque-wide strands at z = 0.5 over a grey plane at z = 0, lit from +Y+Z:
// each strand's shadow lands 0.5 below it on the plane, where the plane's
// light is scaled by exactly T = exp(-opacity) (each strand is many texels
// wide: coverage 1, alpha = opacity), and nowhere else.
TEST(MeshShadows, AClumpOverAPlaneShadowsThePlane) {
    const glm::dvec3 towardsLight(0.0, 1.0, 1.0);
    const std::vector<double> heights{-0.6, 0.4};
    const double width = 0.4, depthAbovePlane = 0.5;
    const float opacity = 0.5f;
    MeshPrim plane = grey(quadGrid(4, "/plane"));
    plane.subdivisionScheme = "none";
    plane.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(-2.0, -2.0, 0.0));
    Scene planeOnly;
    planeOnly.setMesh(plane);
    planeOnly.setLight(distantLightFrom(towardsLight));
    // The plane alone has no hair: only its own depth is drawn, and a flat
    // plane does not shadow itself (checked below: every pixel is lit).
    const RenderResult bare = render(planeOnly);
    EXPECT_FALSE(bare.plan.isEnabled("shadowDepth /light"));
    EXPECT_TRUE(bare.plan.isEnabled("meshShadow /light"));
    EXPECT_EQ(bare.stats.shadowMapsRebuilt, 1u);
    Scene withHair = planeOnly;
    withHair.setCurves(horizontalStrands("/hair", 1, 0, float(depthAbovePlane), heights, width, {1, 1, 1}, opacity));
    const RenderResult shadowed = render(withHair);
    ASSERT_TRUE(shadowed.plan.isEnabled("deepOpacity /light"));

    const double expected = std::exp(-double(opacity));
    size_t inside = 0, outside = 0;
    for (int py = 0; py < kPixels; ++py) {
        for (int px = 0; px < kPixels; ++px) {
            const glm::dvec2 w = worldAt(px, py);
            bool onStrand = false;
            double nearestShadow = 1e9;
            for (double y : heights) {
                onStrand = onStrand || std::abs(w.y - y) < 0.5 * width + kMargin;
                nearestShadow = std::min(nearestShadow, std::abs(w.y - (y - depthAbovePlane)));
            }
            if (onStrand) continue;  // the camera sees the strand there, not the plane
            const size_t i = 4 * (size_t(py) * kPixels + size_t(px));
            for (int c = 0; c < 3; ++c) {
                const double lit = bare.color.pixels[i + size_t(c)];
                ASSERT_GT(lit, 0.01) << "the plane is lit at (" << px << ", " << py << ")";
                const double ratio = shadowed.color.pixels[i + size_t(c)] / lit;
                if (nearestShadow < 0.5 * width - kMargin) {
                    inside += c == 0;
                    ASSERT_NEAR(ratio, expected, 0.01) << "(" << px << ", " << py << ") in a strand's shadow";
                } else if (nearestShadow > 0.5 * width + kMargin) {
                    outside += c == 0;
                    ASSERT_NEAR(ratio, 1.0, 1e-6) << "(" << px << ", " << py << ") out of the shadows";
                }
            }
        }
    }
    // Two stripes about 0.2 units (4 pixels) high across 96 pixels inside;
    // most of the rest of the plane outside.
    EXPECT_GT(inside, 500u);
    EXPECT_GT(outside, 3000u);

    // Moving only the camera keeps the map, the meshes' part included.
    Diagnostics diagnostics;
    const RenderResult moved =
        sharedRenderer().render(withHair, orthographicView(1.1 * kAcross, kPixels), RenderSettings{}, diagnostics);
    EXPECT_EQ(moved.stats.shadowMapsKept, 1u);
    EXPECT_EQ(moved.stats.shadowMapsRebuilt, 0u);
    EXPECT_FALSE(moved.plan.isEnabled("meshShadow /light"));
    EXPECT_FALSE(moved.plan.isEnabled("deepOpacity /light"));
    EXPECT_TRUE(moved.plan.isEnabled("strands"));
}

// A mesh of zero-area faces (every triangle's corners on one line, and one
// corner repeated) between a light and strands: it warns, nothing is drawn
// of it, and the frame stays finite, the strands lit as without it.
TEST(MeshShadows, AMeshOfZeroAreaFacesStaysFinite) {
    MeshPrim flat;
    flat.path = "/degenerate";
    flat.subdivisionScheme = "none";
    flat.points = {{-1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}};
    flat.faceVertexCounts = {3, 3};
    flat.faceVertexIndices = {0, 1, 2, 1, 2, 3};
    Scene strandsOnly;
    strandsOnly.setCurves(horizontalStrands("/hair", 1, 0, 0.0f, {-0.3, 0.0, 0.3}, 0.1, {1, 1, 1}, 0.5f));
    strandsOnly.setLight(distantLightFrom({0.0, 0.0, 1.0}));
    Scene withMesh = strandsOnly;
    withMesh.setMesh(flat);
    const RenderResult bare = render(strandsOnly);
    Diagnostics diagnostics;
    const RenderResult frame =
        sharedRenderer().render(withMesh, orthographicView(kAcross, kPixels), RenderSettings{}, diagnostics);
    EXPECT_NE(warningsText(diagnostics).find("no area"), std::string::npos) << warningsText(diagnostics);
    for (size_t i = 0; i < frame.color.pixels.size(); ++i) {
        ASSERT_TRUE(std::isfinite(frame.color.pixels[i])) << i;
        ASSERT_NEAR(frame.color.pixels[i], bare.color.pixels[i], 1e-6f) << i;
    }
}

namespace {

// A grey 4 x 4 plane at z = 0 about the origin, of quads.
MeshPrim groundPlane(const std::string& path = "/plane") {
    MeshPrim plane = grey(quadGrid(4, path));
    plane.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(-2.0, -2.0, 0.0));
    return plane;
}

// Compares `shadowed` with `unshadowed` (the same scene, shadowMode=off:
// Lambert alone) pixel by pixel: black where `inShadow` says a pixel lies
// well inside a mesh's shadow, equal where it lies well outside, skipped
// between (`inShadow` returns nullopt there and where the camera sees no
// receiver). Returns how many pixels were inside and outside.
std::pair<size_t, size_t> compareShadowed(const RenderResult& shadowed, const RenderResult& unshadowed,
                                          const std::function<std::optional<bool>(glm::dvec2)>& inShadow) {
    size_t inside = 0, outside = 0;
    for (int py = 0; py < kPixels; ++py) {
        for (int px = 0; px < kPixels; ++px) {
            const std::optional<bool> in = inShadow(worldAt(px, py));
            if (!in) continue;
            const size_t i = 4 * (size_t(py) * kPixels + size_t(px));
            for (int c = 0; c < 3; ++c) {
                const float lit = unshadowed.color.pixels[i + size_t(c)], seen = shadowed.color.pixels[i + size_t(c)];
                EXPECT_GT(lit, 0.01f) << "(" << px << ", " << py << ") is lit without shadows";
                if (*in) {
                    EXPECT_LT(seen, 1e-6f) << "(" << px << ", " << py << ") in a mesh's shadow";
                } else {
                    EXPECT_NEAR(seen, lit, 1e-5f * lit) << "(" << px << ", " << py << ") out of the shadows";
                }
            }
            (*in ? inside : outside) += 1;
        }
    }
    return {inside, outside};
}

}  // namespace

// A sphere over a plane, lit from +X+Z: the plane is black inside the
// sphere's shadow, whose outline follows by hand, and lit exactly as
// without shadows outside it; the sphere's own lit side is not darkened
// (a convex mesh cannot shadow its lit side). With or without hair in the
// frame (a strand along y = 1.6 whose own stripe is left out): without
// hair only the meshes' depth is drawn; with it the meshes' view holds both.
class MeshOnMesh : public ::testing::TestWithParam<bool> {};

TEST_P(MeshOnMesh, ASphereShadowsThePlaneAndNotItself) {
    const bool withHair = GetParam();
    const glm::dvec3 towardsLight(1.0, 0.0, 1.0), centre(0.0, 0.0, 1.0);
    const double radius = 0.5, hairY = 1.6, hairWidth = 0.1;
    Scene scene;
    scene.setMesh(groundPlane());
    scene.setMesh(grey(uvSphere("/sphere", glm::vec3(centre), float(radius), 32, 64)));
    scene.setLight(distantLightFrom(towardsLight));
    if (withHair)
        scene.setCurves(horizontalStrands("/hair", 1, 0, 0.5f, {hairY}, hairWidth, {0.9f, 0.7f, 0.5f}, 1.0f));
    const RenderResult shadowed = render(scene);
    const RenderResult unshadowed = render(scene, {"shadowMode=off"});
    ASSERT_TRUE(shadowed.plan.isEnabled("meshShadow /light"));
    EXPECT_EQ(shadowed.plan.isEnabled("deepOpacity /light"), withHair);

    const auto [inside, outside] = compareShadowed(shadowed, unshadowed, [&](glm::dvec2 w) -> std::optional<bool> {
        if (withHair && std::abs(w.y - hairY) < 0.5 * hairWidth + kMargin) return std::nullopt;
        const double fromCentre = glm::length(w - glm::dvec2(centre));
        if (fromCentre < radius + kMargin) {
            // The sphere itself: its lit side, away from the terminator,
            // where n.l is at least 0.2 (the facets' normals are smoothed).
            if (fromCentre > radius - kMargin) return std::nullopt;
            const glm::dvec3 normal(w.x - centre.x, w.y - centre.y,
                                    std::sqrt(radius * radius - fromCentre * fromCentre));
            const double lit = glm::dot(glm::normalize(normal), glm::normalize(towardsLight));
            return lit > 0.2 ? std::optional<bool>(false) : std::nullopt;
        }
        const double outsideBy = outsideSphereShadow({w.x, w.y, 0.0}, towardsLight, centre, radius);
        if (outsideBy < -kMargin) return true;
        if (outsideBy > kMargin) return false;
        return std::nullopt;
    });
    // The shadow is an ellipse 0.71 x 0.5 about (-1, 0): about 0.8 square
    // units well inside, 420 pixels; most of the plane and half the sphere
    // outside.
    EXPECT_GT(inside, 300u);
    EXPECT_GT(outside, 6000u);
}

INSTANTIATE_TEST_SUITE_P(MeshShadows, MeshOnMesh, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& param) { return param.param ? "withHair" : "meshesOnly"; });

// One mesh prim of two parts, a 1 x 1 quad at z = 0.5 over the plane, lit
// from +X+Z: the quad's shadow on its own plane is the square
// x in [-0.5, 0.5], y in [-0.5, 0.5], half of it hidden from the camera
// by the quad (x >= 0).
TEST(MeshShadows, AMeshShadowsItself) {
    MeshPrim mesh = groundPlane("/shelf");
    const int first = int(mesh.points.size());
    // In the plane's local frame (translated by -2, -2): x 2..3, y 1.5..2.5.
    for (glm::vec2 corner : {glm::vec2(2.0f, 1.5f), glm::vec2(3.0f, 1.5f), glm::vec2(3.0f, 2.5f), glm::vec2(2.0f, 2.5f)})
        mesh.points.emplace_back(corner.x, corner.y, 0.5f);
    mesh.faceVertexCounts.push_back(4);
    mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {first, first + 1, first + 2, first + 3});
    Scene scene;
    scene.setMesh(mesh);
    scene.setLight(distantLightFrom({1.0, 0.0, 1.0}));
    const RenderResult shadowed = render(scene);
    const RenderResult unshadowed = render(scene, {"shadowMode=off"});
    const auto [inside, outside] = compareShadowed(shadowed, unshadowed, [](glm::dvec2 w) -> std::optional<bool> {
        const bool onQuad = w.x > -kMargin && w.x < 1.0 + kMargin && std::abs(w.y) < 0.5 + kMargin;
        if (onQuad) return w.x > kMargin && w.x < 1.0 - kMargin && std::abs(w.y) < 0.5 - kMargin
                               ? std::optional<bool>(false)  // the quad's top, lit
                               : std::nullopt;
        if (std::abs(w.x) < 0.5 - kMargin && std::abs(w.y) < 0.5 - kMargin) return true;
        if (std::abs(w.x) > 0.5 + kMargin || std::abs(w.y) > 0.5 + kMargin) return false;
        return std::nullopt;
    });
    // Well inside: x in [-0.4, -0.1], y in [-0.4, 0.4] (the quad hides the
    // rest), about 0.3 x 0.8 units, 140 pixels.
    EXPECT_GT(inside, 120u);
    EXPECT_GT(outside, 7000u);
}
