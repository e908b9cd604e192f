#include "hdHair/environment/LatlongTexture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <glm/vec3.hpp>

#include "hdHair/base/InputError.h"
#include "hdHair/base/RegularFile.h"

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
    // Unassociated: OpenImageIO would otherwise multiply PNG and TIFF colour
    // by their alpha on read; Storm loads the dome with premultiplyAlpha off.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path, &config);
    if (!input) refuse(path, OIIO::geterror());
    const OIIO::ImageSpec spec = input->spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) refuse(path, "the image has no texels");
    if (spec.depth > 1) refuse(path, "a volume image, not a latlong map");
    if (spec.width > kMaxLatlongTextureWidth || spec.height > kMaxLatlongTextureHeight)
        refuse(path, fmt::format("the image declares {} × {} texels, more than the {} × {} hdHair reads for a dome",
                                 spec.width, spec.height, kMaxLatlongTextureWidth, kMaxLatlongTextureHeight));

    LatlongTextureRead read;
    read.imageWidth = spec.width;
    read.imageHeight = spec.height;
    const int channels = spec.nchannels >= 3 ? 3 : 1;
    read.srgbDecoded = (spec.nchannels == 3 || spec.nchannels == 4) && spec.format == OIIO::TypeDesc::UINT8;
    read.grid = latlongGrid(std::min(gridWidth, spec.width), std::min(gridHeight, spec.height));
    RadianceGrid& grid = read.grid;

    std::vector<int> cellColumn(size_t(spec.width));
    for (int x = 0; x < spec.width; ++x) cellColumn[size_t(x)] = int(int64_t(x) * grid.width / spec.width);
    std::vector<glm::dvec3> sums(grid.cellCount(), glm::dvec3(0.0));
    std::vector<double> weights(grid.cellCount(), 0.0);

    const bool tiled = spec.tile_width > 0 && spec.tile_height > 0;
    const int bandRows = tiled ? (kBandRows + spec.tile_height - 1) / spec.tile_height * spec.tile_height : kBandRows;
    std::vector<float> band(size_t(bandRows) * size_t(spec.width) * size_t(channels));
    for (int y0 = 0; y0 < spec.height; y0 += bandRows) {
        const int y1 = std::min(spec.height, y0 + bandRows);
        const bool ok = tiled ? input->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y0, spec.y + y1, spec.z,
                                                  spec.z + 1, 0, channels, OIIO::TypeDesc::FLOAT, band.data())
                              : input->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, channels,
                                                      OIIO::TypeDesc::FLOAT, band.data());
        if (!ok) refuse(path, input->geterror());
        for (int y = y0; y < y1; ++y) {
            // Texels of a row share their solid angle: the row's, per texel.
            const double weight = latlongCellSolidAngle(y, spec.width, spec.height);
            const size_t cellRow = size_t(int64_t(y) * grid.height / spec.height) * size_t(grid.width);
            const float* texel = band.data() + size_t(y - y0) * size_t(spec.width) * size_t(channels);
            for (int x = 0; x < spec.width; ++x, texel += channels) {
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
