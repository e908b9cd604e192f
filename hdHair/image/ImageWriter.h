#pragma once
// Writes rendered images through OpenImageIO, the format chosen by the file
// extension:
// - .exr: half float RGBA, scene-linear, pre-multiplied alpha (EXR's own
//   convention), ZIP compressed;
// - .png, .tif/.tiff: 8-bit sRGB-encoded RGBA (alpha un-premultiplied, as
//   those formats expect);
// - .jpg/.jpeg: 8-bit sRGB RGB, composited over black (no alpha channel).
// Files are written atomically: to a temporary file in the same folder, then
// renamed over the target, so a reader never sees a half-written image and a
// failed render leaves any previous file in place.

#include <string>

#include "hdHair/image/Image.h"

namespace hdhair {

// Throws std::runtime_error naming the path for an unsupported extension, a
// missing folder or a failed write.
void writeImage(const Image& image, const std::string& path);

// True for the extensions writeImage() accepts.
bool isSupportedImagePath(const std::string& path);

// Reads any image OpenImageIO reads, as floats with the file's channels and
// values as stored: 8-bit files give sRGB-encoded values in [0, 1] with
// straight alpha, EXR files linear pre-multiplied values.
Image readImage(const std::string& path);

}  // namespace hdhair
