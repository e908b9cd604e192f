#include "hdHair/curves/HairDensityGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>
#include <tbb/parallel_for.h>

#include "hdHair/curves/CatmullRomEvaluation.h"

namespace hdhair {

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The grid coordinates of a world point: voxel i spans [i, i + 1).
glm::dvec3 gridCoordinates(const DensityGridShape& shape, const glm::dvec3& point) {
    return (point - shape.origin) / shape.voxelSize;
}

// The trilinear weights of the eight voxel centres around `point`: the
// first centre (possibly -1 on an axis) and the fractions toward the next.
struct TrilinearCell {
    glm::ivec3 base;
    glm::dvec3 fraction;
};

bool cellAt(const DensityGridShape& shape, const glm::dvec3& point, TrilinearCell& cell) {
    const glm::dvec3 g = gridCoordinates(shape, point) - 0.5;  // voxel centres at integers
    const glm::dvec3 base = glm::floor(g);
    if (!finite(base) || glm::any(glm::lessThan(base, glm::dvec3(-1.0))) ||
        glm::any(glm::greaterThanEqual(base, glm::dvec3(shape.dims))))
        return false;
    cell = {glm::ivec3(base), g - base};
    return true;
}

// Calls visit(index, weight) for each of the cell's corners inside the grid.
template <typename Visit>
void forEachCorner(const DensityGridShape& shape, const TrilinearCell& cell, Visit visit) {
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 offset(corner & 1, (corner >> 1) & 1, corner >> 2);
        const glm::ivec3 voxel = cell.base + offset;
        if (glm::any(glm::lessThan(voxel, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(voxel, shape.dims)))
            continue;
        const glm::dvec3& f = cell.fraction;
        const double weight = (offset.x ? f.x : 1.0 - f.x) * (offset.y ? f.y : 1.0 - f.y) * (offset.z ? f.z : 1.0 - f.z);
        visit((size_t(voxel.z) * size_t(shape.dims.y) + size_t(voxel.y)) * size_t(shape.dims.x) + size_t(voxel.x),
              weight);
    }
}

// Adds `sigma` (of one voxel's worth) at `point`, spread over the eight
// voxels around it with the trilinear lookup's weights (its adjoint): a
// piece between two voxel centres is not counted whole in one, which would
// alias against pieces of half a voxel (two or three to a voxel).
// Only voxels in z-layers [layers.x, layers.y) are written: the slab of the
// grid the caller owns.
void splat(DensityGrid& grid, const glm::dvec3& point, double sigma, const glm::ivec2& layers) {
    TrilinearCell cell;
    if (!cellAt(grid.shape, point, cell)) return;
    const size_t layerSize = size_t(grid.shape.dims.x) * size_t(grid.shape.dims.y);
    forEachCorner(grid.shape, cell, [&](size_t index, double weight) {
        const int layer = int(index / layerSize);
        if (layer >= layers.x && layer < layers.y) grid.extinction[index] += float(weight * sigma);
    });
}

// The z-layers a span's splat can reach: the span lies within its Bézier
// control polygon's bounds, and the splat reaches the voxel centres either
// side. Empty (x >= y) for a span that is not finite.
glm::ivec2 spanLayers(const DensityGridShape& shape, const StrandControlPoint* controls) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (int i = 0; i < 4; ++i) {
        low = std::min(low, double(controls[i].position.z));
        high = std::max(high, double(controls[i].position.z));
    }
    if (!std::isfinite(low) || !std::isfinite(high)) return glm::ivec2(0);
    const double from = std::floor((low - shape.origin.z) / shape.voxelSize - 0.5);
    const double to = std::floor((high - shape.origin.z) / shape.voxelSize - 0.5) + 2.0;
    return glm::ivec2(int(std::clamp(from, 0.0, double(shape.dims.z))), int(std::clamp(to, 0.0, double(shape.dims.z))));
}

// Cuts span `segment` into pieces no longer than half a voxel and splats
// each into the grid's z-layers `layers` (σ = α w L / V).
void addSpan(DensityGrid& grid, const PreparedCurves& curves, size_t segment, const glm::ivec2& layers) {
    const DensityGridShape& shape = grid.shape;
    const double volume = shape.voxelSize * shape.voxelSize * shape.voxelSize;
    const int maxPieces = 4 * std::max({shape.dims.x, shape.dims.y, shape.dims.z});
    const StrandControlPoint* controls = curves.spanControls(segment);
    const double bound = bezierPolygonLength(controls);
    if (!std::isfinite(bound)) return;
    const int pieces = std::clamp(int(std::ceil(bound / (0.5 * shape.voxelSize))), 1, maxPieces);
    StrandControlPoint previous = evaluate(controls, 0.0f);
    for (int piece = 1; piece <= pieces; ++piece) {
        const StrandControlPoint next = evaluate(controls, float(piece) / float(pieces));
        const double length = glm::length(glm::dvec3(next.position) - glm::dvec3(previous.position));
        const double width = std::max(0.5 * double(previous.width + next.width), 0.0);
        const double opacity = std::clamp(0.5 * double(previous.opacity + next.opacity), 0.0, 1.0);
        const glm::dvec3 middle = 0.5 * (glm::dvec3(previous.position) + glm::dvec3(next.position));
        previous = next;
        splat(grid, middle, opacity * width * length / volume, layers);
    }
}

// Slabs of this many z-layers are filled in parallel.
constexpr int kLayersPerSlab = 4;

}  // namespace

DensityGridShape fitDensityGrid(const glm::dvec3& low, const glm::dvec3& high, size_t maxVoxels) {
    const glm::dvec3 extent = high - low;
    if (!finite(low) || !finite(high) || extent.x < 0.0 || extent.y < 0.0 || extent.z < 0.0 || maxVoxels < 125)
        return {};
    const double longest = std::max({extent.x, extent.y, extent.z});
    // A point (or a flat box) still gets a voxel of some size.
    double voxel = longest > 0.0 ? longest / kMaxDensityVoxelsAlong : 1.0;
    if (!(voxel > 0.0) || !std::isfinite(voxel)) return {};
    auto dimsFor = [&extent](double size) {
        return glm::ivec3(glm::dvec3(4.0) + glm::ceil(glm::max(extent / size, glm::dvec3(1.0))));
    };
    // Coarser until the voxels fit: each step multiplies them by about 0.7.
    for (int step = 0; step < 64; ++step) {
        const glm::ivec3 dims = dimsFor(voxel);
        const double count = double(dims.x) * double(dims.y) * double(dims.z);
        if (count <= double(maxVoxels)) {
            DensityGridShape shape;
            shape.voxelSize = voxel;
            shape.dims = dims;
            // Centred on the box, two voxels of margin all round (at least):
            // the splat spreads a fibre over the voxel centres either side
            // of it, so the outermost voxels stay empty, and the texture's
            // clamp at the edges reads 0 beyond them.
            shape.origin = 0.5 * (low + high) - 0.5 * voxel * glm::dvec3(dims);
            return shape;
        }
        voxel *= std::cbrt(count / double(maxVoxels)) * 1.01;
    }
    return {};
}

void addStrandsToGrid(DensityGrid& grid, const PreparedCurves& curves) {
    const DensityGridShape& shape = grid.shape;
    if (shape.empty()) return;
    // Slab by slab of z-layers, in parallel: each slab takes, in span order,
    // the spans that reach it and adds only to its own layers, so every
    // voxel sums the same pieces in the same order whatever the threads (the
    // frame does not change with the machine's core count).
    const int slabs = (shape.dims.z + kLayersPerSlab - 1) / kLayersPerSlab;
    std::vector<std::vector<size_t>> spansOfSlab(static_cast<size_t>(slabs));
    for (size_t segment = 0; segment < curves.segmentCount(); ++segment) {
        const glm::ivec2 layers = spanLayers(shape, curves.spanControls(segment));
        for (int slab = layers.x / kLayersPerSlab; slab * kLayersPerSlab < layers.y; ++slab)
            spansOfSlab[size_t(slab)].push_back(segment);
    }
    tbb::parallel_for(0, slabs, [&](int slab) {
        const glm::ivec2 layers(slab * kLayersPerSlab, std::min((slab + 1) * kLayersPerSlab, shape.dims.z));
        for (size_t segment : spansOfSlab[size_t(slab)]) addSpan(grid, curves, segment, layers);
    });
}

std::vector<float> halvedDensity(const std::vector<float>& level, const glm::ivec3& dims, glm::ivec3& halvedDims) {
    halvedDims = glm::max(dims / 2, glm::ivec3(1));
    std::vector<float> halved(size_t(halvedDims.x) * size_t(halvedDims.y) * size_t(halvedDims.z), 0.0f);
    if (level.size() != size_t(dims.x) * size_t(dims.y) * size_t(dims.z)) return halved;
    tbb::parallel_for(0, halvedDims.z, [&](int z) {
        for (int y = 0; y < halvedDims.y; ++y)
            for (int x = 0; x < halvedDims.x; ++x) {
                double sum = 0.0;
                int count = 0;
                for (int corner = 0; corner < 8; ++corner) {
                    const glm::ivec3 voxel =
                        2 * glm::ivec3(x, y, z) + glm::ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
                    if (glm::any(glm::greaterThanEqual(voxel, dims))) continue;
                    sum +=
                        level[(size_t(voxel.z) * size_t(dims.y) + size_t(voxel.y)) * size_t(dims.x) + size_t(voxel.x)];
                    ++count;
                }
                halved[(size_t(z) * size_t(halvedDims.y) + size_t(y)) * size_t(halvedDims.x) + size_t(x)] =
                    count > 0 ? float(sum / count) : 0.0f;
            }
    });
    return halved;
}

double extinctionAt(const DensityGrid& grid, const glm::dvec3& point) {
    if (grid.shape.empty()) return 0.0;
    TrilinearCell cell;
    if (!cellAt(grid.shape, point, cell)) return 0.0;
    double sum = 0.0;
    forEachCorner(grid.shape, cell, [&](size_t index, double weight) { sum += weight * double(grid.extinction[index]); });
    return sum;
}

double opticalDepth(const DensityGrid& grid, const glm::dvec3& from, const glm::dvec3& to) {
    const DensityGridShape& shape = grid.shape;
    if (shape.empty() || !finite(from) || !finite(to)) return 0.0;
    // Only the part of the ray inside the grid holds density (slab test).
    const glm::dvec3 low = shape.origin, high = shape.origin + shape.voxelSize * glm::dvec3(shape.dims);
    const glm::dvec3 direction = to - from;
    double enter = 0.0, leave = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (from[axis] < low[axis] || from[axis] > high[axis]) return 0.0;
            continue;
        }
        const double a = (low[axis] - from[axis]) / direction[axis], b = (high[axis] - from[axis]) / direction[axis];
        enter = std::max(enter, std::min(a, b));
        leave = std::min(leave, std::max(a, b));
    }
    const double distance = (leave - enter) * glm::length(direction);
    if (!(distance > 0.0)) return 0.0;
    const int steps = std::max(1, int(std::ceil(distance / (0.5 * shape.voxelSize))));
    const double step = distance / steps;
    double depth = 0.0;
    for (int i = 0; i < steps; ++i)
        depth += step * extinctionAt(grid, from + direction * (enter + (leave - enter) * ((i + 0.5) / steps)));
    return depth;
}

}  // namespace hdhair
