#include "hdHair/environment/RadianceGrid.h"

#include <cmath>
#include <stdexcept>

#include <glm/gtc/constants.hpp>

#include "hdHair/environment/LatlongDirections.h"

namespace hdhair {

float latlongCellSolidAngle(int row, int width, int height) {
    const double top = glm::pi<double>() * row / height;
    const double bottom = glm::pi<double>() * (row + 1) / height;
    return float(glm::two_pi<double>() / width * (std::cos(top) - std::cos(bottom)));
}

RadianceGrid latlongGrid(int width, int height) {
    if (width < 1 || height < 1) throw std::invalid_argument("a latlong grid needs at least one cell");
    RadianceGrid grid;
    grid.width = width;
    grid.height = height;
    const size_t cells = size_t(width) * size_t(height);
    grid.directions.reserve(cells);
    grid.solidAngles.reserve(cells);
    grid.radiance.assign(cells, glm::vec3(0.0f));
    for (int y = 0; y < height; ++y) {
        const float solidAngle = latlongCellSolidAngle(y, width, height);
        for (int x = 0; x < width; ++x) {
            grid.directions.push_back(latlongDirection((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)));
            grid.solidAngles.push_back(solidAngle);
        }
    }
    return grid;
}

}  // namespace hdhair
