#include "hdHair/hydra/RenderBufferWriting.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Imath/half.h>

namespace hdhair::hydra {

size_t bytesPerPixel(BufferFormat format) {
    switch (format) {
    case BufferFormat::Float16Vec4: return 8;
    case BufferFormat::Float32Vec4: return 16;
    case BufferFormat::UNorm8Vec4: return 4;
    case BufferFormat::Float32: return 4;
    case BufferFormat::Int32: return 4;
    }
    return 0;
}

DataWindow clipToBuffer(const DataWindow& window, int bufferWidth, int bufferHeight) {
    int x0 = std::max(window.x, 0), y0 = std::max(window.y, 0);
    int x1 = std::min(window.x + window.width, bufferWidth), y1 = std::min(window.y + window.height, bufferHeight);
    if (x1 <= x0 || y1 <= y0) return DataWindow{};
    return DataWindow{x0, y0, x1 - x0, y1 - y0};
}

namespace {

int channelsOf(BufferFormat format) {
    return (format == BufferFormat::Float32 || format == BufferFormat::Int32) ? 1 : 4;
}

// Calls write(imageRow, imageColumn, bufferPixel) for every pixel of the data
// window that lies inside the buffer.
template <typename WritePixel>
void forEachWindowPixel(const DataWindow& window, int bufferWidth, int bufferHeight, size_t pixelBytes,
                        uint8_t* buffer, WritePixel write) {
    DataWindow clipped = clipToBuffer(window, bufferWidth, bufferHeight);
    for (int y = clipped.y; y < clipped.y + clipped.height; ++y) {
        int imageRow = y - window.y;
        int bufferRow = bufferHeight - 1 - y;  // Hydra's rows run bottom-up
        for (int x = clipped.x; x < clipped.x + clipped.width; ++x) {
            uint8_t* pixel = buffer + (size_t(bufferRow) * size_t(bufferWidth) + size_t(x)) * pixelBytes;
            write(imageRow, x - window.x, pixel);
        }
    }
}

}  // namespace

bool writeImageToBuffer(const Image& image, BufferFormat format, const DataWindow& window, int bufferWidth,
                        int bufferHeight, uint8_t* buffer) {
    if (format == BufferFormat::Int32 || image.channels != channelsOf(format) || image.width != window.width ||
        image.height != window.height || !buffer)
        return false;
    const size_t pixelBytes = bytesPerPixel(format);
    const int channels = image.channels;
    forEachWindowPixel(window, bufferWidth, bufferHeight, pixelBytes, buffer, [&](int row, int column, uint8_t* out) {
        const float* in = &image.pixels[(size_t(row) * size_t(image.width) + size_t(column)) * size_t(channels)];
        for (int c = 0; c < channels; ++c) {
            switch (format) {
            case BufferFormat::Float16Vec4: {
                Imath::half value(in[c]);
                std::memcpy(out + 2 * c, &value, 2);
                break;
            }
            case BufferFormat::UNorm8Vec4:
                out[c] = uint8_t(std::lround(std::clamp(std::isnan(in[c]) ? 0.0f : in[c], 0.0f, 1.0f) * 255.0f));
                break;
            default: std::memcpy(out + 4 * c, &in[c], 4); break;
            }
        }
    });
    return true;
}

bool writeIdsToBuffer(const std::vector<int32_t>& ids, const DataWindow& window, int bufferWidth, int bufferHeight,
                      uint8_t* buffer) {
    if (ids.size() != size_t(window.width) * size_t(window.height) || !buffer) return false;
    forEachWindowPixel(window, bufferWidth, bufferHeight, 4, buffer, [&](int row, int column, uint8_t* out) {
        std::memcpy(out, &ids[size_t(row) * size_t(window.width) + size_t(column)], 4);
    });
    return true;
}

}  // namespace hdhair::hydra
