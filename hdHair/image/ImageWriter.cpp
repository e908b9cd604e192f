#include "hdHair/image/ImageWriter.h"

#include "hdHair/base/AtomicFile.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace hdhair {
namespace fs = std::filesystem;
namespace {

enum class FileKind { Exr, Png, Tiff, Jpeg, Unsupported };

FileKind fileKindOf(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension == ".exr") return FileKind::Exr;
    if (extension == ".png") return FileKind::Png;
    if (extension == ".tif" || extension == ".tiff") return FileKind::Tiff;
    if (extension == ".jpg" || extension == ".jpeg") return FileKind::Jpeg;
    return FileKind::Unsupported;
}

// An ImageBuf over the image's own floats, not a copy of them: a frame is
// 16 bytes a pixel, 200 MB at 4096 px wide, and writing needs none of it
// twice. `channels` (3 or 4) of the image's 4 are written; OpenImageIO only
// reads through the pointer when it writes a file.
OIIO::ImageBuf wrapImage(const Image& image, int channels) {
    if (channels > image.channels)
        throw std::logic_error("writeImage: " + std::to_string(channels) + " channels asked of an image of " +
                               std::to_string(image.channels));
    OIIO::ImageSpec spec(image.width, image.height, channels, OIIO::TypeDesc::FLOAT);
    if (channels == 4) spec.alpha_channel = 3;
    const OIIO::stride_t pixelBytes = OIIO::stride_t(image.channels) * OIIO::stride_t(sizeof(float));
    return OIIO::ImageBuf(spec, const_cast<float*>(image.pixels.data()), pixelBytes);
}

}  // namespace

bool isSupportedImagePath(const std::string& path) { return fileKindOf(path) != FileKind::Unsupported; }

bool isSceneLinearImagePath(const std::string& path) { return fileKindOf(path) == FileKind::Exr; }

bool keepsAlpha(const std::string& path) { return fileKindOf(path) != FileKind::Jpeg; }

namespace {

// Un-premultiplies (or keeps over black) from `linear` into `shown`, which
// may be the same memory: each pixel's alpha is read before it is written.
void makeDisplayImage(const Image& linear, Image& shown, const DisplayTransform& display, bool overBlack) {
    const size_t pixels = size_t(linear.width) * size_t(linear.height);
    for (size_t p = 0; p < pixels; ++p) {
        const float* in = linear.pixels.data() + p * size_t(linear.channels);
        float* out = shown.pixels.data() + 4 * p;
        const float alpha = linear.channels == 4 ? in[3] : 1.0f;
        // Pre-multiplied colour is already "over black"; straight colour
        // divides alpha out where there is any.
        const float scale = overBlack || alpha <= 0.0f ? 1.0f : 1.0f / alpha;
        for (int c = 0; c < 3; ++c) out[c] = in[std::min(c, linear.channels - 1)] * scale;
        out[3] = overBlack ? 1.0f : alpha;
    }
    display.apply(shown.pixels.data(), pixels);
}

}  // namespace

Image displayImage(const Image& linear, const DisplayTransform& display, bool overBlack) {
    Image shown(linear.width, linear.height, 4);
    makeDisplayImage(linear, shown, display, overBlack);
    return shown;
}

Image displayImage(Image&& linear, const DisplayTransform& display, bool overBlack) {
    if (linear.channels != 4) return displayImage(static_cast<const Image&>(linear), display, overBlack);
    Image shown = std::move(linear);
    makeDisplayImage(shown, shown, display, overBlack);
    return shown;
}

ImageWriteReport writeImage(const Image& image, const std::string& path, const ImageColor& color,
                            const ImageMetadata& metadata) {
    ImageWriteReport report;
    FileKind kind = fileKindOf(path);
    if (kind == FileKind::Unsupported)
        throw std::runtime_error("cannot write '" + path +
                                 "': unsupported image extension (use .exr, .png, .tif, .tiff, .jpg or .jpeg)");
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::runtime_error("cannot write '" + path + "': the image is empty or malformed");
    fs::path target = fs::absolute(path);
    if (!fs::is_directory(target.parent_path()))
        throw std::runtime_error("cannot write '" + path + "': folder '" + target.parent_path().string() +
                                 "' does not exist");

    OIIO::ImageBuf out;
    OIIO::TypeDesc format;
    Image clamped, shown;  // only when the written pixels differ from the ones given
    if (kind == FileKind::Exr) {
        if (color.exrFloat32) {
            out = wrapImage(image, image.channels);
            format = OIIO::TypeDesc::FLOAT;
        } else {
            // Counted first: the image is copied to be clamped only when a
            // value is beyond half float's range.
            const size_t channels = size_t(image.channels);
            for (size_t i = 0; i < image.pixels.size(); i += channels) {
                bool beyond = false;
                for (size_t c = i; c < i + channels; ++c)
                    beyond = beyond || std::fabs(image.pixels[c]) > kHalfMax;  // NaN: the renderer replaces those
                report.pixelsClampedToHalf += beyond ? 1 : 0;
            }
            const Image* written = &image;
            if (report.pixelsClampedToHalf > 0) {
                clamped = image;
                for (float& value : clamped.pixels)
                    if (std::fabs(value) > kHalfMax) value = std::copysign(kHalfMax, value);
                written = &clamped;
            }
            out = wrapImage(*written, image.channels);
            format = OIIO::TypeDesc::HALF;
        }
        out.specmod().attribute("compression", "zip");
        // The colour space's name (as hdHair's OCIO config names it) and,
        // in EXR's standard attribute, its primaries and white.
        out.specmod().attribute("colorSpace", toString(color.space));
        for (const auto& [name, value] : metadata) out.specmod().attribute(name, value);
        const std::array<float, 8> chromaticities = chromaticitiesOf(color.space);
        out.specmod().attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities.data());
    } else {
        const bool overBlack = kind == FileKind::Jpeg;
        const Image* displayed = color.displayed;
        if (!displayed) {
            const DisplayTransform srgb = DisplayTransform::create({ColorCorrectionMode::SRGB, "", "", "", "", "",
                                                                    toString(color.space)});
            shown = displayImage(image, color.display ? *color.display : srgb, overBlack);
            displayed = &shown;
        }
        // JPEG has no alpha: its three channels are read from the four.
        out = wrapImage(*displayed, overBlack ? 3 : 4);
        format = OIIO::TypeDesc::UINT8;
        if (!color.display || color.display->mode() == ColorCorrectionMode::SRGB)
            out.specmod().attribute("oiio:ColorSpace", "sRGB");
        else
            out.specmod().attribute("hdhair:displayTransform", color.display->summary());
        if (!overBlack) out.specmod().attribute("oiio:UnassociatedAlpha", 1);
        if (overBlack) out.specmod().attribute("CompressionQuality", 95);
    }
    out.set_write_format(format);

    writeFileAtomically(path, [&](const std::string& temporary) {
        return out.write(temporary) ? std::string() : out.geterror();
    });
    return report;
}

Image readImage(const std::string& path) {
    // Read pixels as stored: without this, OpenImageIO premultiplies PNG and
    // TIFF colour by their straight alpha on read.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    OIIO::ImageBuf buffer(path, 0, 0, nullptr, &config);
    if (!buffer.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error("cannot read image '" + path + "': " + buffer.geterror());
    const OIIO::ImageSpec& spec = buffer.spec();
    Image image(spec.width, spec.height, spec.nchannels);
    buffer.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
    return image;
}

}  // namespace hdhair
