#pragma once
// The hair as a volume: the strands' optical density on a regular grid of
// cubic voxels over their bounds (after Unreal Engine 5's groom renderer,
// which voxelises the strands every frame for shadows and transmittance).
// Light through the hair is attenuated as T = exp(-k ∫ σ ds), with the k of
// the deep opacity maps (hdHair/plan/DeepOpacityLayers.h kShadowExtinction),
// so the two methods agree on what a fibre blocks.
//
// What a fibre adds: a fibre of width w and opacity α crossing a ray at
// right angles blocks α of a width w, the deep opacity maps' opacity of a
// fibre seen across. Spread over a voxel of volume V along a length L of
// it, it adds σ = α w L / V, the mean optical depth per unit length of rays
// crossing the voxel across the fibres. Rays along a fibre meet less of it
// (for fibres at angle θ to the ray, |sin θ| as much); hair is lit across
// its fibres far more often than along them, so this is kept as the one
// density, and its bias along the fibres is documented
// (docs/how-it-works.md, "Hair density volume").
//
// Built on the CPU from the prepared strands, the same Catmull-Rom curves
// the GPU draws, each span cut into pieces no longer than half a voxel,
// each piece's α w L spread over the eight voxels around its middle with
// the lookup's trilinear weights; pieces outside the grid are dropped (the
// grid holds the bounds and a voxel of margin, so none are).

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair {

// The grid's place and size.
struct DensityGridShape {
    glm::dvec3 origin{0.0};  // world position of the grid's lowest corner
    double voxelSize = 0.0;  // world units a voxel's edge
    glm::ivec3 dims{0};      // voxels along x, y, z
    size_t voxelCount() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
    bool empty() const { return voxelCount() == 0 || !(voxelSize > 0.0); }
    bool operator==(const DensityGridShape& other) const {
        return origin == other.origin && voxelSize == other.voxelSize && dims == other.dims;
    }
    bool operator!=(const DensityGridShape& other) const { return !(*this == other); }
};

// At most this many voxels along the grid's longest side: finer than the
// deep opacity maps resolve depth (a few layers) many times over.
constexpr int kMaxDensityVoxelsAlong = 128;

// The grid over the world box [low, high] (the hair's bounds, widths
// included): cubic voxels of the size that gives the longest side
// kMaxDensityVoxelsAlong voxels, or larger so that there are at most
// `maxVoxels`; two voxels of margin all round, so that the splat leaves the
// outermost voxels empty and a lookup beyond the grid reads 0. Empty when
// the box is empty, not finite, or `maxVoxels` holds fewer than 125 voxels.
DensityGridShape fitDensityGrid(const glm::dvec3& low, const glm::dvec3& high, size_t maxVoxels);

struct DensityGrid {
    DensityGridShape shape;
    std::vector<float> extinction;  // σ per voxel (1 / world units), x fastest, then y, then z

    explicit DensityGrid(const DensityGridShape& gridShape = {})
        : shape(gridShape), extinction(gridShape.empty() ? 0 : gridShape.voxelCount(), 0.0f) {}
    float at(int x, int y, int z) const {
        return extinction[(size_t(z) * size_t(shape.dims.y) + size_t(y)) * size_t(shape.dims.x) + size_t(x)];
    }
};

// Adds every span of `curves` to `grid` (σ = α w L / V, above). Spans are
// cut into at most 4 pieces a voxel of the grid's longest side, whatever
// their length, so a strand longer than the grid costs what the grid does.
void addStrandsToGrid(DensityGrid& grid, const PreparedCurves& curves);

// The next level of the grid's mip chain: max(dims / 2, 1) texels, each
// the mean σ of the voxels of `level` under it (the 2 x 2 x 2 whose
// indices halve to its own; an odd side's last voxel, in the empty margin,
// is left out), as OpenGL sizes mip levels. The cone lookups of
// shaders/include/densityVolume.glsl read it: the mean density over a
// cone's cross-section.
std::vector<float> halvedDensity(const std::vector<float>& level, const glm::ivec3& dims, glm::ivec3& halvedDims);

// σ at a world point, trilinear between voxel centres (as the GPU's
// sampler3D filters it), 0 outside the grid.
double extinctionAt(const DensityGrid& grid, const glm::dvec3& point);

// ∫ σ ds from `from` to `to`, by the rule the shaders march it
// (shaders/include/densityVolume.glsl): steps of half a voxel, each step's
// σ at its middle. The reference the GPU's transmittance is tested against.
double opticalDepth(const DensityGrid& grid, const glm::dvec3& from, const glm::dvec3& to);

}  // namespace hdhair
