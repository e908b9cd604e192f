// Every output a frame produces (colour, depth, primId, instanceId,
// elementId), in every transparency mode, on a scene whose pixels follow by
// hand: flat shading, straight strands facing the camera at known distances,
// known opacities. Under blending, depth and ids belong to the nearest strand
// fragment whose alpha (coverage x opacity) is at least 0.1
// (hdHair/plan/NearestStrandRule.h); fainter strands in front still colour
// the pixel but are looked through.

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "HorizontalStrands.h"
#include "StageRendering.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;
using namespace hdhair::testenv;

namespace {

constexpr int kPixels = 64;
constexpr int kColumn = 32;  // every strand crosses the whole image
// Pixel rows (from the top) of the layers below; the strands are 8 px wide.
constexpr int kFrontRow = 16, kFaintRow = 32, kThinRow = 48, kEmptyRow = 60;

// Looking down -Z from z = 10 at [-1.2, 1.2]^2, clipping range [1, 21]: a
// strand at z sits d = 10 - z in front of the camera and, orthographic, at
// window depth (d - 1) / 20.
CameraView orthographicCamera(int pixels = kPixels) {
    CameraPrim camera;
    camera.projection = Projection::Orthographic;
    camera.horizontalAperture = camera.verticalAperture = 24.0f;
    camera.clippingRange = {1.0f, 21.0f};
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 10.0));
    return cameraViewFromPrim(camera, pixels);
}

double pixelsPerUnit(const CameraView& camera) { return camera.projection[0][0] * camera.imageWidth * 0.5; }

// The world height whose image lies `pixels` below the top of the image
// (orthographic: the same at every depth).
double heightAtPixel(const CameraView& camera, double pixels) { return 1.2 - pixels / pixelsPerUnit(camera); }

// The layers, nearest first, and their paths in the order unsorted drawing
// takes them (the scene keeps prims by path): nearest first, so only
// sorting composites them right, and only a depth that ignores drawing order
// is right.
//  - row 16: "front", blue, opacity 0.5 at z = 2, primId 2, instance 3;
//  - row 32: "faint", green, opacity 0.05 at z = 4, primId 3: alpha under 0.1;
//  - row 48: "thin", white, opacity 0.6 at z = 4 but 0.1 px wide, primId 4:
//    drawn 1 px wide (minPixelWidth) at alpha 0.6 x 0.1 = 0.06, under 0.1;
//  - behind all three: "back", red, opaque at z = 0, primId 1, instance 1,
//    one curve per row (elementIds 0, 1, 2);
//  - row 60: nothing.
Scene layeredScene(const CameraView& camera) {
    const double strandWidth = 8.0 / pixelsPerUnit(camera);
    auto rowCentre = [&](int row) { return heightAtPixel(camera, row + 0.5); };
    Scene scene;
    scene.setCurves(horizontalStrands("/a_front", 2, 3, 2.0f, {rowCentre(kFrontRow)}, strandWidth, {0, 0, 1}, 0.5f));
    scene.setCurves(horizontalStrands("/b_faint", 3, 0, 4.0f, {rowCentre(kFaintRow)}, strandWidth, {0, 1, 0}, 0.05f));
    // A quarter pixel below the row's centre: drawn 1 px wide it covers that
    // centre and no other; at its true 0.1 px (opaque path) it covers none.
    scene.setCurves(horizontalStrands("/c_thin", 4, 0, 4.0f, {heightAtPixel(camera, kThinRow + 0.75)},
                                      0.1 / pixelsPerUnit(camera), {1, 1, 1}, 0.6f));
    scene.setCurves(horizontalStrands("/d_back", 1, 1, 0.0f,
                                      {rowCentre(kFrontRow), rowCentre(kFaintRow), rowCentre(kThinRow)}, strandWidth,
                                      {1, 0, 0}, 1.0f));
    return scene;
}

struct ExpectedPixel {
    int row;
    glm::vec4 color;  // pre-multiplied
    float depth;
    int primId, instanceId, elementId;
};

// Window depths (d - 1) / 20.
constexpr float kFrontDepth = 0.35f;  // z = 2: d = 8
constexpr float kFaintDepth = 0.25f;  // z = 4: d = 6
constexpr float kBackDepth = 0.45f;   // z = 0: d = 10
const ExpectedPixel kEmpty{kEmptyRow, glm::vec4(0.0f), 1.0f, -1, -1, -1};

// Sorted over, front to back (binSorted and exact): C = c_front + (1 - a_front) c_back.
const std::vector<ExpectedPixel> kSorted = {
    {kFrontRow, {0.5f, 0.0f, 0.5f, 1.0f}, kFrontDepth, 2, 3, 0},  // blue 0.5 over red
    {kFaintRow, {0.95f, 0.05f, 0.0f, 1.0f}, kBackDepth, 1, 1, 1},  // green 0.05 over red: red's depth and ids
    {kThinRow, {1.0f, 0.06f, 0.06f, 1.0f}, kBackDepth, 1, 1, 2},   // white 0.06 over red: 0.06 + 0.94 red
    kEmpty,
};
// Unsorted: nearest drawn first, then the opaque red over it replaces it.
// Depth and ids are those of the sorted modes: they do not depend on order.
const std::vector<ExpectedPixel> kUnsorted = {
    {kFrontRow, {1.0f, 0.0f, 0.0f, 1.0f}, kFrontDepth, 2, 3, 0},
    {kFaintRow, {1.0f, 0.0f, 0.0f, 1.0f}, kBackDepth, 1, 1, 1},
    {kThinRow, {1.0f, 0.0f, 0.0f, 1.0f}, kBackDepth, 1, 1, 2},
    kEmpty,
};
// Opaque: opacity and coverage ignored, true widths: the nearest strand
// drawn wins, faint or not; the 0.1 px strand covers no pixel centre.
const std::vector<ExpectedPixel> kOpaque = {
    {kFrontRow, {0.0f, 0.0f, 1.0f, 1.0f}, kFrontDepth, 2, 3, 0},
    {kFaintRow, {0.0f, 1.0f, 0.0f, 1.0f}, kFaintDepth, 3, 0, 0},
    {kThinRow, {1.0f, 0.0f, 0.0f, 1.0f}, kBackDepth, 1, 1, 2},
    kEmpty,
};

RenderResult render(const Scene& scene, const CameraView& camera, const std::vector<std::string>& settings,
                    bool ids) {
    RenderSettings renderSettings;
    renderSettings.set("shadingModel", "flat");
    for (const std::string& assignment : settings) renderSettings.setFromAssignment(assignment);
    Diagnostics diagnostics;
    RenderResult result = sharedRenderer().render(scene, camera, renderSettings, diagnostics, RenderOutputs{ids});
    EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front().message;
    return result;
}

// Colours are float, composited in RGBA32F; depths are the rasteriser's
// interpolated window depth.
constexpr float kColorTolerance = 1e-4f;
constexpr float kDepthTolerance = 1e-5f;

void expectOutputs(const RenderResult& result, const std::vector<ExpectedPixel>& expected, bool ids,
                   const std::string& what) {
    ASSERT_EQ(result.depth.width, kPixels);
    for (const ExpectedPixel& pixel : expected) {
        const std::string where = what + ", row " + std::to_string(pixel.row);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(result.color.at(kColumn, pixel.row, c), pixel.color[c], kColorTolerance)
                << where << ", colour channel " << c;
        EXPECT_NEAR(result.depth.at(kColumn, pixel.row, 0), pixel.depth, kDepthTolerance) << where << ", depth";
        if (!ids) continue;
        const size_t index = size_t(pixel.row) * kPixels + kColumn;
        EXPECT_EQ(result.primIds.at(index), pixel.primId) << where << ", primId";
        EXPECT_EQ(result.instanceIds.at(index), pixel.instanceId) << where << ", instanceId";
        EXPECT_EQ(result.elementIds.at(index), pixel.elementId) << where << ", elementId";
    }
}

}  // namespace

TEST(RenderOutputs, EveryOutputInEveryTransparencyModeWithAndWithoutIds) {
    CameraView camera = orthographicCamera();
    Scene scene = layeredScene(camera);
    struct Mode {
        const char* transparency;
        const std::vector<ExpectedPixel>* expected;
    };
    for (Mode mode : {Mode{"binSorted", &kSorted}, Mode{"exact", &kSorted}, Mode{"unsorted", &kUnsorted},
                      Mode{"opaque", &kOpaque}}) {
        // Depth must not depend on whether the host also asked for ids.
        for (bool ids : {false, true}) {
            RenderResult result = render(scene, camera, {std::string("transparency=") + mode.transparency}, ids);
            EXPECT_EQ(result.stats.transparency, mode.transparency);
            expectOutputs(result, *mode.expected, ids,
                          std::string(mode.transparency) + (ids ? " with ids" : " without ids"));
        }
    }
}

// A pixel that only faint strands cover has nothing to pick: depth 1 and ids
// -1 under blending, however many faint strands are drawn over it.
TEST(RenderOutputs, PixelsUnderOnlyFaintStrandsHaveNoIds) {
    CameraView camera = orthographicCamera();
    const double width = 8.0 / pixelsPerUnit(camera);
    Scene scene;
    scene.setCurves(horizontalStrands("/faint", 3, 0, 4.0f, {heightAtPixel(camera, kFaintRow + 0.5)}, width, {0, 1, 0},
                                      0.05f));
    scene.setCurves(horizontalStrands("/fainter", 5, 0, 2.0f, {heightAtPixel(camera, kFaintRow + 0.5)}, width,
                                      {0, 0, 1}, 0.02f));
    // Sorted: green 0.05 (z = 4, in front) over blue 0.02; unsorted draws by
    // path, /faint then /fainter over it: blue 0.02 over green 0.05.
    const ExpectedPixel sorted{kFaintRow, {0.0f, 0.05f, 0.95f * 0.02f, 0.05f + 0.95f * 0.02f}, 1.0f, -1, -1, -1};
    const ExpectedPixel unsorted{kFaintRow, {0.0f, 0.98f * 0.05f, 0.02f, 0.02f + 0.98f * 0.05f}, 1.0f, -1, -1, -1};
    for (const char* mode : {"binSorted", "exact", "unsorted"}) {
        RenderResult result = render(scene, camera, {std::string("transparency=") + mode}, true);
        expectOutputs(result, {std::string(mode) == "unsorted" ? unsorted : sorted}, true, mode);
    }
}

TEST(RenderOutputs, MultisampledOpaqueFramesKeepDepthAndIds) {
    CameraView camera = orthographicCamera();
    Scene scene = layeredScene(camera);
    // The thin strand's row is left out: its 0.1 px may reach a sample.
    std::vector<ExpectedPixel> expected;
    for (const ExpectedPixel& pixel : kOpaque)
        if (pixel.row != kThinRow) expected.push_back(pixel);
    expectOutputs(render(scene, camera, {"transparency=opaque", "msaaSamples=4"}, true), expected, true,
                  "opaque, 4x MSAA");
}

TEST(RenderOutputs, LightBatchesAfterTheFirstLeaveDepthAndIdsAlone) {
    // Lit and split into two light passes: the colour changes, depth and ids
    // must not.
    CameraView camera = orthographicCamera();
    Scene scene = layeredScene(camera);
    for (const char* path : {"/keyLight", "/fillLight"}) {
        LightPrim light;
        light.path = path;
        scene.setLight(light);
    }
    for (const char* mode : {"binSorted", "exact"}) {
        RenderResult result = render(scene, camera,
                                     {std::string("transparency=") + mode, "shadingModel=kajiyaKay", "lightsPerPass=1"},
                                     true);
        EXPECT_EQ(result.stats.lightPasses, 2u) << mode;
        for (const ExpectedPixel& pixel : kSorted) {
            const size_t index = size_t(pixel.row) * kPixels + kColumn;
            EXPECT_NEAR(result.depth.at(kColumn, pixel.row, 0), pixel.depth, kDepthTolerance) << mode << " " << pixel.row;
            EXPECT_EQ(result.primIds.at(index), pixel.primId) << mode << " " << pixel.row;
            EXPECT_EQ(result.elementIds.at(index), pixel.elementId) << mode << " " << pixel.row;
        }
    }
}

TEST(RenderOutputs, ExactOverItsMemoryBudgetFallsBackWithDepthAndIdsIntact) {
    // 40 sheets covering a 128 x 128 image make 655,360 fragments, more than
    // exactMemoryMB=16 holds (524,288): the frame is redrawn binSorted, and
    // the ids it no longer gets from the exact resolve need the ids pass.
    // Sheet i lies at z = 4 - 0.1 i; all are 5% opaque but sheet 10, at
    // z = 3 (d = 7, window depth 0.3), which is half opaque.
    CameraView camera = orthographicCamera(128);
    Scene scene;
    for (int i = 0; i < 40; ++i)
        scene.setCurves(horizontalStrands("/sheet" + std::to_string(i), 100 + i, 0, 4.0f - 0.1f * float(i), {0.0},
                                          10.0, {1, 1, 1}, i == 10 ? 0.5f : 0.05f));
    RenderSettings settings;
    settings.set("shadingModel", "flat");
    settings.set("transparency", "exact");
    settings.set("exactMemoryMB", "16");
    for (bool ids : {false, true}) {
        Diagnostics diagnostics;
        RenderResult result = sharedRenderer().render(scene, camera, settings, diagnostics, RenderOutputs{ids});
        ASSERT_EQ(result.stats.transparency, "binSorted") << "the frame did not fall back";
        EXPECT_EQ(result.plan.isEnabled("ids"), ids);
        EXPECT_NEAR(result.depth.at(64, 64, 0), 0.3f, kDepthTolerance) << (ids ? "with ids" : "without ids");
        if (!ids) continue;
        EXPECT_EQ(result.primIds.at(64 * 128 + 64), 110);
        EXPECT_EQ(result.elementIds.at(64 * 128 + 64), 0);
    }
}

TEST(RenderOutputs, PerspectiveDepthIsWindowDepthOfTheNearestQualifyingStrand) {
    // A camera at z = 10 with a 20 x 20 aperture and focal length 50 (it sees
    // 4 units across at distance 10), clipping range [n, f] = [1, 21]. A
    // point at distance d has z_ndc = (f + n) / (f - n) - 2 f n / ((f - n) d),
    // window depth (z_ndc + 1) / 2 = f / (f - n) * (1 - n / d).
    CameraPrim prim;
    prim.horizontalAperture = prim.verticalAperture = 20.0f;
    prim.focalLength = 50.0f;
    prim.clippingRange = {1.0f, 21.0f};
    prim.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 10.0));
    CameraView camera = cameraViewFromPrim(prim, kPixels);
    // Through the image centre: a half-opaque strand at z = 2 over an opaque
    // one at z = 0, and a 5% one in front of both at z = 4.
    Scene scene;
    scene.setCurves(horizontalStrands("/front", 2, 0, 2.0f, {0.0}, 0.5, {0, 0, 1}, 0.5f));
    scene.setCurves(horizontalStrands("/faint", 3, 0, 4.0f, {0.0}, 0.5, {0, 1, 0}, 0.05f));
    scene.setCurves(horizontalStrands("/back", 1, 0, 0.0f, {0.0}, 0.5, {1, 0, 0}, 1.0f));
    const float front = 21.0f / 20.0f * (1.0f - 1.0f / 8.0f);   // d = 8: 0.91875
    const float faint = 21.0f / 20.0f * (1.0f - 1.0f / 6.0f);   // d = 6: 0.875
    const int centre = kPixels / 2, corner = 1;
    for (const char* mode : {"binSorted", "exact", "unsorted", "opaque"}) {
        RenderResult result = render(scene, camera, {std::string("transparency=") + mode}, false);
        const bool opaque = std::string(mode) == "opaque";
        EXPECT_NEAR(result.depth.at(centre, centre, 0), opaque ? faint : front, kDepthTolerance) << mode;
        EXPECT_EQ(result.depth.at(centre, corner, 0), 1.0f) << mode << ": nothing above the strands";
    }
}
