// The hair density volume on the CPU (HairDensityGrid.h): a slab of fibres
// of known spacing has the density and the transmittance e^(-σd) worked
// out by hand, and the hard cases stay finite and bounded.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/HairDensityGrid.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using test::authoredPrimvar;

namespace {

// Straight linear strands, one a point pair.
PreparedCurves strands(const std::vector<std::pair<glm::vec3, glm::vec3>>& ends, float width, float opacity) {
    CurvesPrim prim;
    prim.path = "/strands";
    prim.type = CurveType::Linear;
    for (const auto& [from, to] : ends) {
        prim.curveVertexCounts.push_back(2);
        prim.points.push_back(from);
        prim.points.push_back(to);
    }
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Constant, 1, {width});
    prim.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Constant, 1, {opacity});
    Diagnostics diagnostics;
    return prepareCurves(prim, diagnostics);
}

DensityGrid gridOf(const PreparedCurves& curves, size_t maxVoxels = size_t(1) << 22) {
    DensityGrid grid(fitDensityGrid(glm::dvec3(curves.boundsMin), glm::dvec3(curves.boundsMax), maxVoxels));
    addStrandsToGrid(grid, curves);
    return grid;
}

// Σ σ V: the α w L the grid holds.
double heldOpacityLength(const DensityGrid& grid) {
    const double volume = std::pow(grid.shape.voxelSize, 3.0);
    return volume * std::accumulate(grid.extinction.begin(), grid.extinction.end(), 0.0);
}

// A slab of fibres along x, 2 units long, in a lattice of pitch p in y and
// z: y in [-1, 1], z in [0, D]. Fibre length per unit volume is 1/p², so
// σ = α w / p² inside (5 here), and a ray along z through the whole slab has
// optical depth σ D = 2 (the fibre layers it crosses, D/p, each covering
// w/p of it, α each). The grid is held to 4,096 voxels, about 0.09 units
// each: some 45 rows of fibres a voxel, so the lattice's rows against the
// voxels' edges change a voxel's density by about 2 %.
constexpr double kPitch = 0.002, kDepth = 0.4, kWidth = 4e-5, kOpacity = 0.5;
constexpr size_t kSlabVoxels = 4096;
const double kSigma = kOpacity * kWidth / (kPitch * kPitch);

PreparedCurves slab(double opacity = kOpacity) {
    std::vector<std::pair<glm::vec3, glm::vec3>> ends;
    for (double y = -1.0 + 0.5 * kPitch; y < 1.0; y += kPitch)
        for (double z = 0.5 * kPitch; z < kDepth; z += kPitch)
            ends.push_back({glm::vec3(-1.0f, float(y), float(z)), glm::vec3(1.0f, float(y), float(z))});
    return strands(ends, float(kWidth), float(opacity));
}

}  // namespace

// The slab's density and its depth, by hand, within 3 % (the lattice
// against the voxels).
TEST(HairDensityGrid, ASlabOfKnownDensityHasItsTransmittance) {
    const PreparedCurves fibres = slab();
    const DensityGrid grid = gridOf(fibres, kSlabVoxels);
    ASSERT_FALSE(grid.shape.empty());
    EXPECT_NEAR(extinctionAt(grid, {0.0, 0.0, 0.5 * kDepth}) / kSigma, 1.0, 0.03);
    // Through the whole slab, from outside to outside: σ D.
    const double through = opticalDepth(grid, {0.1, 0.2, -1.0}, {0.1, 0.2, 2.0});
    EXPECT_NEAR(through / (kSigma * kDepth), 1.0, 0.03);
    EXPECT_NEAR(std::exp(-through) / std::exp(-kSigma * kDepth), 1.0, 0.03 * kSigma * kDepth);
    // From outside to the slab's middle: half of it.
    const double half = opticalDepth(grid, {0.1, 0.2, -1.0}, {0.1, 0.2, 0.5 * kDepth});
    EXPECT_NEAR(half / (0.5 * kSigma * kDepth), 1.0, 0.03);
    // Nothing beside the slab.
    EXPECT_EQ(opticalDepth(grid, {0.1, 0.2, kDepth + 2.0 * grid.shape.voxelSize}, {0.1, 0.2, 3.0}), 0.0);
    // Every fibre's α w L is held: nothing dropped at the bounds.
    EXPECT_NEAR(heldOpacityLength(grid) / (kOpacity * kWidth * 2.0 * double(fibres.curveCount)), 1.0, 1e-4);
}

// What the checks above must catch: the slab at half the density, and the
// grid looked up one voxel off (as a wrong origin in the shader would).
TEST(HairDensityGrid, MutationsFailTheSlab) {
    const DensityGrid halved = gridOf(slab(0.5 * kOpacity), kSlabVoxels);
    EXPECT_GT(std::abs(opticalDepth(halved, {0.1, 0.2, -1.0}, {0.1, 0.2, 2.0}) / (kSigma * kDepth) - 1.0), 0.03);
    DensityGrid offset = gridOf(slab(), kSlabVoxels);
    offset.shape.origin.z += offset.shape.voxelSize;
    const double half = opticalDepth(offset, {0.1, 0.2, -1.0}, {0.1, 0.2, 0.5 * kDepth});
    EXPECT_GT(std::abs(half / (0.5 * kSigma * kDepth) - 1.0), 0.03);
}

// All the hair within one voxel's size: a grid of a few voxels holding it
// all, finite.
TEST(HairDensityGrid, AllHairInOneVoxelIsHeld) {
    const PreparedCurves tiny = strands({{glm::vec3(0.0f), glm::vec3(1e-4f, 0.0f, 0.0f)}}, 1e-5f, 1.0f);
    const DensityGrid grid = gridOf(tiny);
    ASSERT_FALSE(grid.shape.empty());
    EXPECT_NEAR(heldOpacityLength(grid) / (1e-5 * 1e-4), 1.0, 1e-3);
    for (float sigma : grid.extinction) ASSERT_TRUE(std::isfinite(sigma));
    EXPECT_TRUE(std::isfinite(opticalDepth(grid, {-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0})));
}

// A strand a million units long, bent through the grid: its pieces are
// capped by the grid's size, not its length, and all of it is held.
TEST(HairDensityGrid, AStrandLongerThanTheGridCostsTheGrid) {
    CurvesPrim prim;
    prim.path = "/long";
    prim.type = CurveType::Cubic;
    prim.basis = CurveBasis::CatmullRom;
    prim.curveVertexCounts = {4};
    prim.points = {{-5e5f, 0.0f, 0.0f}, {-5e5f, 1.0f, 0.0f}, {5e5f, 1.0f, 0.0f}, {5e5f, 0.0f, 0.0f}};
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Constant, 1, {1.0f});
    Diagnostics diagnostics;
    const PreparedCurves curves = prepareCurves(prim, diagnostics);
    const DensityGrid grid = gridOf(curves);
    ASSERT_FALSE(grid.shape.empty());
    EXPECT_LE(grid.shape.voxelCount(), size_t(1) << 22);
    for (float sigma : grid.extinction) ASSERT_TRUE(std::isfinite(sigma) && sigma >= 0.0f);
    EXPECT_GT(heldOpacityLength(grid), 0.9e6);  // at least the straight middle, 1e6 long
}

// Zero-width strands block nothing; a non-finite or empty box and a budget
// under 5 x 5 x 5 voxels (one and its margin) make no grid.
TEST(HairDensityGrid, ZeroWidthAndDegenerateInputsGiveNoDensity) {
    const DensityGrid grid = gridOf(strands({{glm::vec3(-1.0f), glm::vec3(1.0f)}}, 0.0f, 1.0f));
    EXPECT_EQ(heldOpacityLength(grid), 0.0);
    EXPECT_EQ(opticalDepth(grid, glm::dvec3(-2.0), glm::dvec3(2.0)), 0.0);
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(fitDensityGrid({0, 0, 0}, {inf, 1, 1}, 1000).empty());
    EXPECT_TRUE(fitDensityGrid({nan, 0, 0}, {1, 1, 1}, 1000).empty());
    EXPECT_TRUE(fitDensityGrid({1, 1, 1}, {0, 0, 0}, 1000).empty());
    EXPECT_TRUE(fitDensityGrid({0, 0, 0}, {1, 1, 1}, 124).empty());
}

// The budget decides the voxel size: at most maxVoxels, the box held; with
// room, the longest side has kMaxDensityVoxelsAlong voxels and a margin.
TEST(HairDensityGrid, TheBudgetCoarsensTheVoxels) {
    const DensityGridShape roomy = fitDensityGrid({-1.0, -0.5, 0.0}, {3.0, 0.5, 0.25}, size_t(1) << 30);
    EXPECT_EQ(roomy.dims.x, kMaxDensityVoxelsAlong + 4);
    for (size_t budget : {size_t(125), size_t(1000), size_t(100000), size_t(1) << 24}) {
        const DensityGridShape shape = fitDensityGrid({-1.0, -0.5, 0.0}, {3.0, 0.5, 0.25}, budget);
        ASSERT_FALSE(shape.empty()) << budget;
        EXPECT_LE(shape.voxelCount(), budget);
        const glm::dvec3 high = shape.origin + shape.voxelSize * glm::dvec3(shape.dims);
        EXPECT_LE(shape.origin.x, -1.0);
        EXPECT_GE(high.x, 3.0);
        EXPECT_LE(shape.origin.z, 0.0);
        EXPECT_GE(high.z, 0.25);
    }
}

// The mip chain's next level, by hand: a 4 x 2 x 3 grid whose voxel (x, y,
// z) holds x + 10 y + 100 z halves to 2 x 1 x 1, each texel the mean of the
// 2 x 2 x 2 voxels under it (z = 2, the odd side's last layer, left out):
// 55.5 and 57.5. A grid of one voxel stays one voxel. A level of the wrong
// size halves to zeros, not past its end.
TEST(HairDensityGrid, TheMipChainHalvesToTheMeanOfTheVoxelsUnderEachTexel) {
    const glm::ivec3 dims(4, 2, 3);
    std::vector<float> level;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) level.push_back(float(x + 10 * y + 100 * z));
    glm::ivec3 halvedDims;
    const std::vector<float> halved = hdhair::halvedDensity(level, dims, halvedDims);
    EXPECT_EQ(halvedDims, glm::ivec3(2, 1, 1));
    ASSERT_EQ(halved.size(), 2u);
    EXPECT_FLOAT_EQ(halved[0], 55.5f);  // x 0-1, y 0-1, z 0-1: 0.5 + 5 + 50
    EXPECT_FLOAT_EQ(halved[1], 57.5f);  // x 2-3
    glm::ivec3 oneDims;
    EXPECT_EQ(hdhair::halvedDensity({3.0f}, glm::ivec3(1), oneDims), std::vector<float>{3.0f});
    EXPECT_EQ(oneDims, glm::ivec3(1));
    EXPECT_EQ(hdhair::halvedDensity({1.0f, 2.0f}, dims, halvedDims), std::vector<float>(2, 0.0f));
}
