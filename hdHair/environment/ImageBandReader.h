#pragma once
// An image file read a band of rows at a time, as float: what
// LatlongTexture.h averages onto its grid. OpenImageIO does the decoding
// (OiioImageBandReader.h); which copy of it a program reaches is chosen when
// it is linked (CMakeLists.txt here):
// - LinkedImageBandReader.cpp: programs that link OpenImageIO anyway
//   (hdhair-record writes its images with it; the tests; hdhair-bench).
// - LoadedImageBandReader.cpp: the Hydra plugin. OpenImageIO and the ~280
//   libraries it pulls in cost a host noticeable time and resident memory to
//   load on every launch (docs/performance.md, "Storm side by side");
//   most stages have no dome texture, so the plugin leaves the decoder in a
//   module of its own, hdHairImageReader.so beside hdHair.so, and loads it
//   with dlopen the first time a dome texture is read.

#include <memory>
#include <string>

namespace hdhair {

// What the file declares, before a texel is read.
struct ImageBandLayout {
    int width = 0;        // the data window, in texels
    int height = 0;
    int depth = 1;        // more than 1: a volume
    int channels = 0;     // as stored
    bool eightBit = false;  // 8-bit unsigned channels (sRGB-encoded when RGB(A))
    int tileHeight = 0;   // rows a tile holds; 0 for a scanline file
};

class ImageBandReader {
public:
    virtual ~ImageBandReader() = default;
    virtual const ImageBandLayout& layout() const = 0;
    // Rows [y0, y1) of the first `channels` channels as float, row-major,
    // into `pixels` ((y1 - y0) × width × channels floats). A tiled file is
    // read in whole tiles, so y0 and y1 are multiples of tileHeight or y1 is
    // the height. Returns "" on success, else why not.
    virtual std::string readRows(int y0, int y1, int channels, float* pixels) = 0;
};

// `path` opened for reading, with alpha left unassociated (PNG and TIFF
// colour is not multiplied by it). Returns null with `why` set when the file
// cannot be opened or decoded, or when the decoder itself cannot be loaded.
std::unique_ptr<ImageBandReader> openImageBandReader(const std::string& path, std::string& why);

}  // namespace hdhair
