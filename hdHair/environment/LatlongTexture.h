#pragma once
// Reads a DomeLight's latlong texture through OpenImageIO (ImageBandReader.h;
// the plugin loads it on first use) straight onto the coarse grid the SRBF
// fit uses (RadianceGrid.h), a band of rows at a time: a 16k map never sits
// in memory whole, only its grid and one band.
//
// - Formats: whatever OpenImageIO reads (EXR, HDR, TIFF, PNG, ...); the
//   first subimage, its full-resolution level, its data window.
// - Colour, as Storm's automatic source colour space (hioOiio's
//   IsColorSpaceSRGB, OpenUSD 24.08): 8-bit images with 3 or 4 channels are
//   sRGB-encoded and are decoded to linear; everything else (EXR, HDR, 16-bit
//   and float TIFF, 1- and 2-channel images) is linear as stored. Channels 0-2
//   are RGB; a 1- or 2-channel image is grey (channel 0), as Storm swizzles
//   it. Alpha is ignored (read unassociated, so it darkens nothing), as Storm
//   samples the dome's .rgb.
// - Texels with a NaN, infinite or negative channel have that channel read as
//   0 (Storm shows NaN texels as black; an infinite or negative radiance has
//   no meaning for a light) and are counted in repairedTexels, for the
//   caller's warning.
// - Averaging: each texel goes to the grid cell its centre falls in,
//   weighted by its solid angle (rows near the poles cover less of the
//   sphere), so a cell's radiance is the mean over the cell's solid angle.
//   The grid is at most the image's own size in each direction.
// - Refused before a texel is read, with InputError "cannot read '<file>':
//   why": a path that is not a regular file (a directory, a device), a file
//   OpenImageIO cannot open or decode, a volume (depth > 1), and an image
//   declaring more than kMaxLatlongTextureWidth × kMaxLatlongTextureHeight
//   texels, however large the header says it is.

#include <cstddef>
#include <string>

#include "hdHair/environment/RadianceGrid.h"

namespace hdhair {

// 32k × 16k: larger than any published HDRI (16k × 8k), small enough that a
// band of rows stays under 64 MB.
constexpr int kMaxLatlongTextureWidth = 32768;
constexpr int kMaxLatlongTextureHeight = 16384;

struct LatlongTextureRead {
    RadianceGrid grid;            // the texture averaged onto the grid, in the dome's frame
    int imageWidth = 0;           // the file's size in texels
    int imageHeight = 0;
    bool srgbDecoded = false;     // an 8-bit RGB(A) image, decoded from sRGB
    size_t repairedTexels = 0;    // texels with a NaN, infinite or negative channel (read as 0)
};

// The texture at `path` averaged onto a gridWidth × gridHeight grid (fewer
// cells where the image has fewer texels). Throws InputError as above.
LatlongTextureRead readLatlongTexture(const std::string& path, int gridWidth, int gridHeight);

}  // namespace hdhair
