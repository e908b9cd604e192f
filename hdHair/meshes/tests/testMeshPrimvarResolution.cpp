// resolveMeshPrimvar: a mesh's element count per interpolation, and the
// shared repairs (indices, tuple size, non-finite values) with their warnings.

#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/MeshPrimvarResolution.h"
#include "hdHair/meshes/MeshTopology.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using hdhair::test::quadGrid;
using hdhair::test::warningsText;

namespace {

// The bottom row of a 2 x 2 grid: 2 faces, 9 points (the top row unused), 8 corners.
MeshTopology twoQuads() {
    MeshPrim mesh = quadGrid(2);
    mesh.faceVertexCounts = {4, 4};
    mesh.faceVertexIndices.resize(8);
    Diagnostics diagnostics;
    return checkMeshTopology(mesh, diagnostics);
}

// `count` grey levels 0, 0.1, 0.2, ... as colours.
std::vector<float> greys(size_t count) {
    std::vector<float> values;
    for (size_t i = 0; i < count; ++i) values.insert(values.end(), 3, 0.1f * float(i));
    return values;
}

ResolvedPrimvar resolve(const Primvar& primvar, Diagnostics& diagnostics) {
    return resolveMeshPrimvar(primvar, twoQuads(), kFallbackDisplayColor, "/grid", "displayColor", diagnostics);
}

}  // namespace

TEST(MeshPrimvarResolution, EachInterpolationTakesItsMeshCount) {
    struct Case {
        Interpolation interpolation;
        size_t count;
    };
    // UsdGeomMesh: uniform per face, vertex and varying per point,
    // faceVarying per face corner.
    for (const Case& c : {Case{Interpolation::Uniform, 2}, Case{Interpolation::Vertex, 9},
                          Case{Interpolation::Varying, 9}, Case{Interpolation::FaceVarying, 8}}) {
        Diagnostics diagnostics;
        const ResolvedPrimvar resolved =
            resolve(authoredPrimvar("displayColor", c.interpolation, 3, greys(c.count)), diagnostics);
        EXPECT_EQ(diagnostics.warningCount(), 0u) << toString(c.interpolation) << warningsText(diagnostics);
        EXPECT_EQ(resolved.interpolation, c.interpolation);
        EXPECT_EQ(resolved.values, greys(c.count));
    }
}

TEST(MeshPrimvarResolution, AWrongCountFallsBackNamingPrimPrimvarAndCounts) {
    for (Interpolation interpolation :
         {Interpolation::Uniform, Interpolation::Vertex, Interpolation::Varying, Interpolation::FaceVarying}) {
        Diagnostics diagnostics;
        const ResolvedPrimvar resolved =
            resolve(authoredPrimvar("displayColor", interpolation, 3, greys(5)), diagnostics);
        EXPECT_EQ(resolved.interpolation, Interpolation::Constant);
        EXPECT_EQ(resolved.values, kFallbackDisplayColor);
        const size_t expected = interpolation == Interpolation::Uniform       ? 2
                                : interpolation == Interpolation::FaceVarying ? 8
                                                                              : 9;
        EXPECT_EQ(warningsText(diagnostics),
                  "/grid.primvars:displayColor: " + std::string(toString(interpolation)) + " interpolation needs " +
                      std::to_string(expected) + " values, found 5; using the fallback (0.5, 0.5, 0.5)\n");
    }
}

TEST(MeshPrimvarResolution, IndexedFaceVaryingIsFlattenedPerCorner) {
    Primvar primvar = authoredPrimvar("displayColor", Interpolation::FaceVarying, 3, greys(2));
    primvar.indices = {0, 1, 1, 0, 1, 1, 0, 7};
    Diagnostics diagnostics;
    const ResolvedPrimvar resolved = resolve(primvar, diagnostics);
    ASSERT_EQ(resolved.elementCount(), 8u);
    EXPECT_EQ(resolved.element(1)[0], 0.1f);
    EXPECT_EQ(resolved.element(6)[0], 0.0f);
    EXPECT_EQ(resolved.element(7)[0], 0.5f);  // out of range: the fallback
    EXPECT_EQ(warningsText(diagnostics),
              "/grid.primvars:displayColor: 1 index is out of range for 2 values (first: indices[7] = 7); using the "
              "fallback (0.5, 0.5, 0.5) for it\n");
}

TEST(MeshPrimvarResolution, OneValueIsConstantAndSeveralConstantsKeepTheFirst) {
    Diagnostics diagnostics;
    EXPECT_EQ(resolve(authoredPrimvar("displayColor", Interpolation::Vertex, 3, greys(1)), diagnostics).interpolation,
              Interpolation::Constant);
    const ResolvedPrimvar several =
        resolve(authoredPrimvar("displayColor", Interpolation::Constant, 3, {0.2f, 0.3f, 0.4f, 1, 1, 1}), diagnostics);
    EXPECT_EQ(several.values, (std::vector<float>{0.2f, 0.3f, 0.4f}));
    EXPECT_EQ(warningsText(diagnostics),
              "/grid.primvars:displayColor: constant interpolation needs 1 value, found 2; using the first\n");
}

TEST(MeshPrimvarResolution, WrongTupleSizeAndNonFiniteValuesAreRepaired) {
    Diagnostics diagnostics;
    const ResolvedPrimvar pairs =
        resolve(authoredPrimvar("displayColor", Interpolation::Uniform, 2, {1, 1, 1, 1}), diagnostics);
    EXPECT_EQ(pairs.values, kFallbackDisplayColor);
    std::vector<float> values = greys(2);
    values[4] = std::numeric_limits<float>::quiet_NaN();
    const ResolvedPrimvar uniform =
        resolve(authoredPrimvar("displayColor", Interpolation::Uniform, 3, values), diagnostics);
    EXPECT_EQ(uniform.values, (std::vector<float>{0, 0, 0, 0.5f, 0.5f, 0.5f}));
    EXPECT_EQ(warningsText(diagnostics),
              "/grid.primvars:displayColor: expects 3 components per element, found 2 (untyped); using the fallback "
              "(0.5, 0.5, 0.5)\n"
              "/grid.primvars:displayColor: 1 element is not finite (first: element 1); using the fallback "
              "(0.5, 0.5, 0.5) for it\n");
}
