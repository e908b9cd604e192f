#pragma once
// Writes rendered images through OpenImageIO, the format chosen by the file
// extension:
// - .exr: half float RGBA, scene-linear, pre-multiplied alpha (EXR's own
//   convention), ZIP compressed, with its colour space's name and
//   chromaticities in the metadata; values beyond half float's range
//   (magnitude over 65504) are clamped to it and counted, since a half
//   cannot hold them and would store infinity. ImageColor::exrFloat32
//   writes 32-bit floats instead, every value exactly;
// - .png, .tif/.tiff: 8-bit RGBA through the display transform (alpha
//   un-premultiplied first, as those formats expect);
// - .jpg/.jpeg: 8-bit RGB through the display transform, composited over
//   black (no alpha channel).
// Without a display transform, display formats get the sRGB curve.
// Files are written atomically: to a temporary file in the same folder, then
// renamed over the target, so a reader never sees a half-written image and a
// failed render leaves any previous file in place.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "hdHair/image/ColorSpaces.h"
#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/Image.h"

namespace hdhair {

// Extra string attributes an EXR carries (name, value): what made it, such
// as a path-traced reference's sample count and seed.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

struct ImageColor {
    RenderingSpace space = RenderingSpace::LinearRec709;  // the linear image's space
    const DisplayTransform* display = nullptr;  // for display formats; nullptr: sRGB
    // The display image, when it was made elsewhere (the GPU path): used as
    // it is instead of applying `display`.
    const Image* displayed = nullptr;
    // EXR: 32-bit float channels (hdhair-record --exrFloat32) instead of half.
    bool exrFloat32 = false;
};

// The largest finite half float.
constexpr float kHalfMax = 65504.0f;

struct ImageWriteReport {
    // Pixels with a channel beyond +-kHalfMax, clamped to it in a half EXR.
    size_t pixelsClampedToHalf = 0;
};

// Throws std::runtime_error naming the path for an unsupported extension, a
// missing folder or a failed write.
// `metadata`: extra EXR attributes (ignored by the display formats).
ImageWriteReport writeImage(const Image& linear, const std::string& path, const ImageColor& color = {},
                            const ImageMetadata& metadata = {});

// True for scene-linear formats (.exr), which no display transform touches.
bool isSceneLinearImagePath(const std::string& path);
// True when the format keeps alpha (its display image is un-premultiplied);
// false for JPEG, whose display image is the colour over black.
bool keepsAlpha(const std::string& path);
// The display image a display format stores: `linear` (pre-multiplied)
// un-premultiplied, or over black when `overBlack`, through `display`.
Image displayImage(const Image& linear, const DisplayTransform& display, bool overBlack);
// The same made in the linear image's own memory (RGBA only; others are
// copied): for callers done with the linear pixels, a frame less of memory.
Image displayImage(Image&& linear, const DisplayTransform& display, bool overBlack);

// True for the extensions writeImage() accepts.
bool isSupportedImagePath(const std::string& path);

// Reads any image OpenImageIO reads, as floats with the file's channels and
// values as stored: 8-bit files give sRGB-encoded values in [0, 1] with
// straight alpha, EXR files linear pre-multiplied values.
Image readImage(const std::string& path);

}  // namespace hdhair
