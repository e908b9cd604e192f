#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/base/InputError.h"
#include "hdHair/usda/Stage.h"
#include "hdHair/usda/XformOps.h"

using namespace hdhair;
using namespace hdhair::usda;

namespace {

// One prim "/A" with the given attribute lines.
std::unique_ptr<Stage> stageWith(const std::string& attributes) {
    return Stage::openFromString("#usda 1.0\n\ndef Xform \"A\"\n{\n" + attributes + "\n}\n",
                                 "xform.usda");
}

glm::dvec3 transformPoint(const glm::dmat4& m, glm::dvec3 p) {
    return glm::dvec3(m * glm::dvec4(p, 1.0));
}

void expectNear(glm::dvec3 actual, glm::dvec3 expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-6);
    EXPECT_NEAR(actual.y, expected.y, 1e-6);
    EXPECT_NEAR(actual.z, expected.z, 1e-6);
}

LocalTransform local(const std::string& attributes, double time = 0.0) {
    std::unique_ptr<Stage> stage = stageWith(attributes);
    const Prim* prim = stage->findPrim("/A");
    EXPECT_NE(prim, nullptr);
    return computeLocalTransform(*prim, time);
}

}  // namespace

TEST(XformOps, NoXformOpOrderIsIdentity) {
    LocalTransform t = local("double3 xformOp:translate = (1, 2, 3)");
    EXPECT_EQ(t.matrix, glm::dmat4(1.0));
    EXPECT_FALSE(t.resetsXformStack);
}

TEST(XformOps, LastOpIsAppliedFirst) {
    // xformOpOrder [translate, rotateZ]: the point is rotated, then moved.
    // (1,0,0) -> rotateZ 90 -> (0,1,0) -> translate (1,2,3) -> (1,3,3).
    LocalTransform t = local(R"(
        double3 xformOp:translate = (1, 2, 3)
        float xformOp:rotateZ = 90
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateZ"])");
    expectNear(transformPoint(t.matrix, {1, 0, 0}), {1, 3, 3});
    // The other order: moved, then rotated about the origin.
    // (1,0,0) -> (2,2,3) -> (-2,2,3).
    LocalTransform u = local(R"(
        double3 xformOp:translate = (1, 2, 3)
        float xformOp:rotateZ = 90
        uniform token[] xformOpOrder = ["xformOp:rotateZ", "xformOp:translate"])");
    expectNear(transformPoint(u.matrix, {1, 0, 0}), {-2, 2, 3});
}

TEST(XformOps, TranslateRotateScaleScalesFirst) {
    // The USD documentation's [translate, rotate, scale]: scale, rotate, translate.
    // (1,0,0) -> scale 2 -> (2,0,0) -> rotateXYZ (0,0,90) -> (0,2,0) -> (10,2,0).
    LocalTransform t = local(R"(
        double3 xformOp:translate = (10, 0, 0)
        float3 xformOp:rotateXYZ = (0, 0, 90)
        float3 xformOp:scale = (2, 2, 2)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ", "xformOp:scale"])");
    expectNear(transformPoint(t.matrix, {1, 0, 0}), {10, 2, 0});
}

TEST(XformOps, RotationOrdersApplyTheFirstLetterFirst) {
    // rotateXYZ (90, 90, 0): X first: (0,1,0) -> (0,0,1), then Y: -> (1,0,0).
    LocalTransform xyz = local(R"(
        float3 xformOp:rotateXYZ = (90, 90, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"])");
    expectNear(transformPoint(xyz.matrix, {0, 1, 0}), {1, 0, 0});
    // rotateZYX (90, 90, 0): Y first: (0,1,0) stays, then X: -> (0,0,1).
    LocalTransform zyx = local(R"(
        float3 xformOp:rotateZYX = (90, 90, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateZYX"])");
    expectNear(transformPoint(zyx.matrix, {0, 1, 0}), {0, 0, 1});

    // Every order against its definition as three single-axis rotations.
    const double angles[3] = {30, 45, 60};
    const char* orders[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};
    for (const char* order : orders) {
        glm::dmat4 m;
        ASSERT_TRUE(xformOpMatrix(std::string("rotate") + order, {30, 45, 60}, &m));
        glm::dmat4 expected(1.0);
        for (int i = 0; i < 3; ++i) {
            int axis = order[i] - 'X';
            glm::dvec3 direction(0.0);
            direction[axis] = 1.0;
            glm::dmat4 single;
            ASSERT_TRUE(xformOpMatrix(std::string("rotate") + order[i], {angles[axis]}, &single));
            EXPECT_EQ(single, glm::rotate(glm::dmat4(1.0), glm::radians(angles[axis]), direction));
            expected = single * expected;
        }
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], 1e-12) << order;
    }
}

TEST(XformOps, PivotWithInvertedOp) {
    // Rotate 90 degrees about Z around the pivot (1,0,0): (2,0,0) -> (1,1,0).
    LocalTransform t = local(R"(
        float3 xformOp:translate:pivot = (1, 0, 0)
        float xformOp:rotateZ = 90
        uniform token[] xformOpOrder = ["xformOp:translate:pivot", "xformOp:rotateZ", "!invert!xformOp:translate:pivot"])");
    expectNear(transformPoint(t.matrix, {2, 0, 0}), {1, 1, 0});
    expectNear(transformPoint(t.matrix, {1, 0, 0}), {1, 0, 0});
}

TEST(XformOps, InvertedScale) {
    LocalTransform t = local(R"(
        float3 xformOp:scale = (2, 4, 8)
        uniform token[] xformOpOrder = ["!invert!xformOp:scale"])");
    expectNear(transformPoint(t.matrix, {1, 1, 1}), {0.5, 0.25, 0.125});
}

TEST(XformOps, AdjacentInversePairCancelsEvenWithoutItsAttribute) {
    // UsdGeomXformable skips an op next to its own inverse before looking the
    // attribute up.
    LocalTransform t = local(R"(
        double3 xformOp:translate = (1, 0, 0)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:translate:pivot", "!invert!xformOp:translate:pivot"])");
    expectNear(transformPoint(t.matrix, {0, 0, 0}), {1, 0, 0});
}

TEST(XformOps, OrientIsRealFirst) {
    // (w, x, y, z) = (cos 45, 0, 0, sin 45): 90 degrees about +Z.
    LocalTransform t = local(R"(
        quatf xformOp:orient = (0.70710678, 0, 0, 0.70710678)
        uniform token[] xformOpOrder = ["xformOp:orient"])");
    expectNear(transformPoint(t.matrix, {1, 0, 0}), {0, 1, 0});
    // Not normalised in the file: normalised here.
    LocalTransform u = local(R"(
        quatd xformOp:orient = (2, 0, 0, 2)
        uniform token[] xformOpOrder = ["xformOp:orient"])");
    expectNear(transformPoint(u.matrix, {1, 0, 0}), {0, 1, 0});
}

TEST(XformOps, TransformMatrixIsRowVectorAsWritten) {
    // Translation in the last row, as USD writes it.
    LocalTransform t = local(R"(
        matrix4d xformOp:transform = ( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (5, 6, 7, 1) )
        uniform token[] xformOpOrder = ["xformOp:transform"])");
    expectNear(transformPoint(t.matrix, {1, 1, 1}), {6, 7, 8});
    // A row-vector rotation by 90 degrees about Z: its first row is the image of +X.
    LocalTransform r = local(R"(
        matrix4d xformOp:transform = ( (0, 1, 0, 0), (-1, 0, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1) )
        uniform token[] xformOpOrder = ["xformOp:transform"])");
    expectNear(transformPoint(r.matrix, {1, 0, 0}), {0, 1, 0});
    expectNear(transformPoint(r.matrix, {0, 1, 0}), {-1, 0, 0});
}

TEST(XformOps, ResetXformStackDropsEarlierOps) {
    LocalTransform t = local(R"(
        double3 xformOp:translate = (1, 2, 3)
        float3 xformOp:scale = (2, 2, 2)
        uniform token[] xformOpOrder = ["!resetXformStack!", "xformOp:translate", "xformOp:scale"])");
    EXPECT_TRUE(t.resetsXformStack);
    expectNear(transformPoint(t.matrix, {1, 0, 0}), {3, 2, 3});
    // Ops before the marker are discarded, as GetOrderedXformOps does.
    LocalTransform u = local(R"(
        double3 xformOp:translate = (1, 2, 3)
        float3 xformOp:scale = (2, 2, 2)
        uniform token[] xformOpOrder = ["xformOp:translate", "!resetXformStack!", "xformOp:scale"])");
    EXPECT_TRUE(u.resetsXformStack);
    expectNear(transformPoint(u.matrix, {1, 0, 0}), {2, 0, 0});
}

TEST(XformOps, TimeSamplesAreEvaluatedAtTheTime) {
    const std::string attributes = R"(
        double3 xformOp:translate.timeSamples = { 0: (0, 0, 0), 10: (10, 0, 0) }
        uniform token[] xformOpOrder = ["xformOp:translate"])";
    expectNear(transformPoint(local(attributes, 5.0).matrix, {0, 0, 0}), {5, 0, 0});
    expectNear(transformPoint(local(attributes, 10.0).matrix, {0, 0, 0}), {10, 0, 0});
    expectNear(transformPoint(local(attributes, 20.0).matrix, {0, 0, 0}), {10, 0, 0});
}

TEST(XformOps, DeclaredOrBlockedOpIsIdentity) {
    LocalTransform t = local(R"(
        double3 xformOp:translate = None
        float xformOp:rotateZ
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateZ"])");
    EXPECT_EQ(t.matrix, glm::dmat4(1.0));
}

TEST(XformOps, MissingOpAttributeNamesFileLineAndOp) {
    try {
        local(R"(
        double3 xformOp:translate = (1, 2, 3)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateY"])");
        FAIL() << "expected InputError";
    } catch (const InputError& error) {
        std::string message = error.what();
        EXPECT_NE(message.find("xform.usda:3"), std::string::npos) << message;
        EXPECT_NE(message.find("/A"), std::string::npos) << message;
        EXPECT_NE(message.find("xformOp:rotateY"), std::string::npos) << message;
    }
}

TEST(XformOps, UnknownOpTypeAndWrongShapeAreInputErrors) {
    const char* const cases[] = {
        R"(
        double3 xformOp:twist = (1, 2, 3)
        uniform token[] xformOpOrder = ["xformOp:twist"])",
        R"(
        float xformOp:translate = 1
        uniform token[] xformOpOrder = ["xformOp:translate"])",
        R"(
        token xformOp:rotateX = "up"
        uniform token[] xformOpOrder = ["xformOp:rotateX"])",
        R"(
        double3 xformOp:translate = (1, 2, 3)
        uniform token[] xformOpOrder = ["translate"])",
    };
    for (const char* attributes : cases) EXPECT_THROW(local(attributes), InputError) << attributes;
}

TEST(XformOps, OpValueCounts) {
    EXPECT_EQ(opValueCount("translate"), 3u);
    EXPECT_EQ(opValueCount("scale"), 3u);
    EXPECT_EQ(opValueCount("rotateY"), 1u);
    EXPECT_EQ(opValueCount("rotateYXZ"), 3u);
    EXPECT_EQ(opValueCount("orient"), 4u);
    EXPECT_EQ(opValueCount("transform"), 16u);
    EXPECT_EQ(opValueCount("rotateXXZ"), 0u);
    EXPECT_EQ(opValueCount("rotateW"), 0u);
    EXPECT_EQ(opValueCount("shear"), 0u);
    glm::dmat4 m;
    EXPECT_FALSE(xformOpMatrix("translate", {1, 2}, &m));
}
