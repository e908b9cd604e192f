#include "hdHair/environment/LatlongTexture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "hdHair/base/InputError.h"
#include "hdHair/base/RegularFile.h"
#include "hdHair/environment/ImageBandReader.h"

namespace hdhair {

namespace {

// Rows read at once (rounded up to whole tiles for a tiled file).
constexpr int kBandRows = 64;

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw InputError("cannot read '" + path + "': " + why);
}

float srgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

LatlongTextureRead readLatlongTexture(const std::string& path, int gridWidth, int gridHeight) {
    if (std::string problem = regularFileProblem(path); !problem.empty()) refuse(path, problem);
    std::string why;
    std::unique_ptr<ImageBandReader> input = openImageBandReader(path, why);
    if (!input) refuse(path, why);
    const ImageBandLayout& layout = input->layout();
    if (layout.width < 1 || layout.height < 1 || layout.channels < 1) refuse(path, "the image has no texels");
    if (layout.depth > 1) refuse(path, "a volume image, not a latlong map");
    if (layout.width > kMaxLatlongTextureWidth || layout.height > kMaxLatlongTextureHeight)
        refuse(path, fmt::format("the image declares {} × {} texels, more than the {} × {} hdHair reads for a dome",
                                 layout.width, layout.height, kMaxLatlongTextureWidth, kMaxLatlongTextureHeight));

    LatlongTextureRead read;
    read.imageWidth = layout.width;
    read.imageHeight = layout.height;
    const int channels = layout.channels >= 3 ? 3 : 1;
    read.srgbDecoded = (layout.channels == 3 || layout.channels == 4) && layout.eightBit;
    read.grid = latlongGrid(std::min(gridWidth, layout.width), std::min(gridHeight, layout.height));
    RadianceGrid& grid = read.grid;

    std::vector<int> cellColumn(size_t(layout.width));
    for (int x = 0; x < layout.width; ++x) cellColumn[size_t(x)] = int(int64_t(x) * grid.width / layout.width);
    std::vector<glm::dvec3> sums(grid.cellCount(), glm::dvec3(0.0));
    std::vector<double> weights(grid.cellCount(), 0.0);

    const bool tiled = layout.tileHeight > 0;
    const int bandRows = tiled ? (kBandRows + layout.tileHeight - 1) / layout.tileHeight * layout.tileHeight : kBandRows;
    std::vector<float> band(size_t(bandRows) * size_t(layout.width) * size_t(channels));
    for (int y0 = 0; y0 < layout.height; y0 += bandRows) {
        const int y1 = std::min(layout.height, y0 + bandRows);
        if (std::string failure = input->readRows(y0, y1, channels, band.data()); !failure.empty())
            refuse(path, failure);
        for (int y = y0; y < y1; ++y) {
            // Texels of a row share their solid angle: the row's, per texel.
            const double weight = latlongCellSolidAngle(y, layout.width, layout.height);
            const size_t cellRow = size_t(int64_t(y) * grid.height / layout.height) * size_t(grid.width);
            const float* texel = band.data() + size_t(y - y0) * size_t(layout.width) * size_t(channels);
            for (int x = 0; x < layout.width; ++x, texel += channels) {
                glm::vec3 value(texel[0], texel[channels > 1 ? 1 : 0], texel[channels > 1 ? 2 : 0]);
                bool repaired = false;
                for (int c = 0; c < 3; ++c) {
                    if (read.srgbDecoded) value[c] = srgbToLinear(value[c]);
                    if (!(std::isfinite(value[c]) && value[c] >= 0.0f)) {
                        value[c] = 0.0f;
                        repaired = true;
                    }
                }
                read.repairedTexels += repaired ? 1 : 0;
                const size_t cell = cellRow + size_t(cellColumn[size_t(x)]);
                sums[cell] += weight * glm::dvec3(value);
                weights[cell] += weight;
            }
        }
    }
    for (size_t cell = 0; cell < grid.cellCount(); ++cell) grid.radiance[cell] = glm::vec3(sums[cell] / weights[cell]);
    return read;
}

}  // namespace hdhair
