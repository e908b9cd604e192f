#pragma once
// Copies what the engine rendered into the memory of Hydra render buffers.
// No pxr here, so it is unit-tested without OpenUSD.
//
// Hydra's CPU buffers are tightly packed with row 0 at the BOTTOM (the
// glReadPixels order that usdrecord's writer and the pick task assume); the
// engine's images run from the top down. The frame covers the camera
// framing's data window, given in y-down pixel coordinates of the buffer;
// pixels outside it are left as they are (the host cleared them).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hdHair/image/Image.h"

namespace hdhair::hydra {

// The HdFormat values hdHair writes (a subset of pxr/imaging/hd/types.h).
enum class BufferFormat { Float16Vec4, Float32Vec4, UNorm8Vec4, Float32, Int32 };

size_t bytesPerPixel(BufferFormat format);

// A rectangle of the buffer, y down: x in [x, x + width), y in [y, y + height).
struct DataWindow {
    int x = 0, y = 0, width = 0, height = 0;
};

// Writes a float image (colour: 4 channels, pre-multiplied; depth: 1
// channel) sized like the data window. Float16 values are rounded to the
// nearest half; UNorm8 values are clamped to [0, 1] and rounded. Returns
// false, writing nothing, when the formats or sizes do not fit.
bool writeImageToBuffer(const Image& image, BufferFormat format, const DataWindow& window, int bufferWidth,
                        int bufferHeight, uint8_t* buffer);

// Writes an id image (one int per pixel, top-down) into an Int32 buffer.
bool writeIdsToBuffer(const std::vector<int32_t>& ids, const DataWindow& window, int bufferWidth, int bufferHeight,
                      uint8_t* buffer);

// The data window clipped to the buffer; empty when they do not overlap.
DataWindow clipToBuffer(const DataWindow& window, int bufferWidth, int bufferHeight);

}  // namespace hdhair::hydra
