#pragma once
// A latlong environment averaged onto a coarse grid of cells: the samples
// the SRBF fit works on (SrbfFit.h). Fitting a 1024 × 512 map texel by texel
// would cost 256 times what fitting its 64 × 32 average does, and the
// narrowest SRBF the paper allows (λ = 64, an angular standard deviation of
// about 1/√λ = 7.2°) is still wider than a 64 × 32 cell (5.6°).
//
// Cells follow the latlong layout of LatlongDirections.h: cell (x, y) covers
// u in [x, x + 1] / width and v in [y, y + 1] / height, row 0 at the top
// (+Y). Its solid angle is exact, (2π / width) (cos θ_top − cos θ_bottom)
// with θ = πv, so the cells' solid angles sum to 4π and sums over cells
// weighted by them are integrals over the sphere.

#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

struct RadianceGrid {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> directions;  // each cell's centre (u, v), unit, in the dome's frame
    std::vector<float> solidAngles;     // steradians
    std::vector<glm::vec3> radiance;    // mean linear RGB radiance over the cell

    size_t cellCount() const { return directions.size(); }
};

// A width × height grid (each at least 1) with every cell's direction and
// solid angle, and zero radiance.
RadianceGrid latlongGrid(int width, int height);

// The solid angle of one cell of row `row` in a width × height latlong grid.
float latlongCellSolidAngle(int row, int width, int height);

}  // namespace hdhair
