// Which defects apply to a stage (BaselineDefects.h), on scenes built in
// code where the answer is known: the baseline test checks only the defects
// this says apply, so a rule that wrongly said "does not apply" would
// silently check less.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "BaselineDefects.h"
#include "OrthographicView.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using namespace hdhair::testenv;
using hdhair::test::authoredPrimvar;

namespace {

// A strand through `points`, 0.05 wide (2 px in the view below), flat grey.
CurvesPrim strand(const std::string& path, CurveType type, std::vector<glm::vec3> points,
                  std::vector<float> widths = {0.05f}) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = type;
    prim.basis = CurveBasis::CatmullRom;
    prim.curveVertexCounts = {int(points.size())};
    prim.points = std::move(points);
    Interpolation widthInterpolation = widths.size() == 1 ? Interpolation::Constant : Interpolation::Vertex;
    prim.primvars["widths"] = authoredPrimvar("widths", widthInterpolation, 1, widths);
    return prim;
}

// Two linear strands, crossing at the origin or side by side.
Scene twoStrands(bool crossing) {
    Scene scene;
    scene.setCurves(strand("/a", CurveType::Linear, {{-1, 0, 0}, {1, 0, 0}}));
    scene.setCurves(crossing ? strand("/b", CurveType::Linear, {{0, -1, 0}, {0, 1, 0}})
                             : strand("/b", CurveType::Linear, {{-1, 0.5f, 0}, {1, 0.5f, 0}}));
    return scene;
}

RenderPlan planTaking(TransparencyPath path) {
    FrameRecipe recipe;
    recipe.transparency.path = path;
    return RenderPlan(recipe, FrameGraph());
}

std::vector<std::string> defectNames(const Scene& scene, TransparencyPath path = TransparencyPath::BinSorted) {
    StageRenderRequest baseline;
    baseline.complexity = Complexity::Medium;
    std::vector<std::string> names;
    for (const BaselineDefect& defect : defectsThatApply(scene, baseline, planTaking(path), orthographicView(2.4, 96)))
        names.push_back(defect.name);
    return names;
}

const std::string kSortingOff = "sorting off (transparency=unsorted)";
const std::string kKd = "Kd 1 -> 0.9", kKs = "Ks 0.35 -> 0.5005", kShininess = "shininess 60 -> 30";
const std::string kCoarser = "complexity medium -> low";

}  // namespace

TEST(BaselineDefects, SortingOffAppliesWhereBlendedStrandsCross) {
    EXPECT_EQ(defectNames(twoStrands(true)), (std::vector<std::string>{kSortingOff, kKd, kKs, kShininess}));
    EXPECT_EQ(defectNames(twoStrands(false)), (std::vector<std::string>{kKd, kKs, kShininess}))
        << "side by side, no pixel holds both";
    EXPECT_EQ(defectNames(twoStrands(true), TransparencyPath::Opaque),
              (std::vector<std::string>{kKd, kKs, kShininess}))
        << "nothing blends";
}

TEST(BaselineDefects, KajiyaKayWeightsApplyWhereAPrimUsesThemWithoutAuthoringThem) {
    Scene scene = twoStrands(false);
    for (const char* path : {"/a", "/b"}) {
        CurvesPrim prim = *scene.findCurves(path);
        prim.shadingModel = "marschner";
        scene.setCurves(prim);
    }
    EXPECT_TRUE(defectNames(scene).empty()) << "Marschner ignores Kd, Ks and shininess; no light to remove";
    CurvesPrim kajiyaKay = *scene.findCurves("/a");
    kajiyaKay.shadingModel = "kajiyaKay";
    kajiyaKay.primvars["hdHair:kajiyaKay:specular"] =
        authoredPrimvar("hdHair:kajiyaKay:specular", Interpolation::Constant, 1, {0.8f});
    scene.setCurves(kajiyaKay);
    EXPECT_EQ(defectNames(scene), (std::vector<std::string>{kKd, kShininess})) << "the prim authors its own Ks";
}

TEST(BaselineDefects, ALightAppliesWhereSomethingIsLit) {
    Scene scene = twoStrands(false);
    LightPrim light;
    light.path = "/key";
    scene.setLight(light);
    EXPECT_EQ(defectNames(scene), (std::vector<std::string>{kKd, kKs, kShininess, "without the light /key"}));
    for (const char* path : {"/a", "/b"}) {
        CurvesPrim prim = *scene.findCurves(path);
        prim.shadingModel = "flat";
        scene.setCurves(prim);
    }
    EXPECT_TRUE(defectNames(scene).empty()) << "flat strands are not lit";
}

TEST(BaselineDefects, ACoarserTessellationAppliesWhereASpanBendsOrVariesNonLinearly) {
    auto coarserApplies = [](const CurvesPrim& prim) {
        Scene scene;
        scene.setCurves(prim);
        std::vector<std::string> names = defectNames(scene);
        return std::find(names.begin(), names.end(), kCoarser) != names.end();
    };
    const std::vector<glm::vec3> straight = {{-1, 0, 0}, {-0.5f, 0, 0}, {0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}};
    EXPECT_FALSE(coarserApplies(strand("/s", CurveType::Cubic, straight))) << "a straight, even strand";
    EXPECT_FALSE(coarserApplies(strand("/s", CurveType::Cubic, straight, {0.05f, 0.04f, 0.03f, 0.02f, 0.01f})))
        << "a linear taper along even spans";
    EXPECT_TRUE(coarserApplies(strand("/s", CurveType::Cubic, straight, {0.05f, 0.05f, 0.02f, 0.05f, 0.05f})))
        << "a width that bulges";
    const std::vector<glm::vec3> wave = {{-1, 0, 0}, {-0.5f, 0.3f, 0}, {0, 0, 0}, {0.5f, 0.3f, 0}, {1, 0, 0}};
    EXPECT_TRUE(coarserApplies(strand("/s", CurveType::Cubic, wave))) << "a wave";
    EXPECT_FALSE(coarserApplies(strand("/s", CurveType::Linear, {{-1, 0, 0}, {-0.5f, 0.3f, 0}, {0, 0, 0}})))
        << "linear spans are straight";
}
