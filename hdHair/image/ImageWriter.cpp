#include "hdHair/image/ImageWriter.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <random>
#include <stdexcept>

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

OIIO::ImageBuf toImageBuf(const Image& image) {
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    if (image.channels == 4) spec.alpha_channel = 3;
    OIIO::ImageBuf buffer(spec);
    buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
    return buffer;
}

// Pre-multiplied scene-linear -> un-premultiplied sRGB (8-bit formats).
OIIO::ImageBuf toDisplaySrgb(const OIIO::ImageBuf& linear, bool keepAlpha) {
    OIIO::ImageBuf source = linear;
    if (!keepAlpha && linear.nchannels() == 4) {
        // No alpha in the file: pre-multiplied colour is already "over black".
        source = OIIO::ImageBufAlgo::channels(linear, 3, {0, 1, 2});
    }
    OIIO::ImageBuf encoded = OIIO::ImageBufAlgo::colorconvert(source, "linear", "sRGB", /*unpremult=*/true);
    if (encoded.has_error() || !encoded.initialized())
        throw std::runtime_error("converting to sRGB failed: " + encoded.geterror());
    if (keepAlpha && linear.nchannels() == 4) {
        // colorconvert re-premultiplies; PNG and TIFF store straight alpha.
        encoded = OIIO::ImageBufAlgo::unpremult(encoded);
    }
    return encoded;
}

std::string temporarySibling(const fs::path& target) {
    std::random_device device;
    std::uniform_int_distribution<unsigned> digits(0, 0xffffff);
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "%06x", digits(device));
    // Keep the extension last: OpenImageIO picks the format from it.
    return (target.parent_path() / ("." + target.stem().string() + ".tmp-" + suffix +
                                    target.extension().string())).string();
}

}  // namespace

bool isSupportedImagePath(const std::string& path) { return fileKindOf(path) != FileKind::Unsupported; }

void writeImage(const Image& image, const std::string& path) {
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

    OIIO::ImageBuf linear = toImageBuf(image);
    OIIO::ImageBuf out;
    OIIO::TypeDesc format;
    if (kind == FileKind::Exr) {
        out = linear;
        format = OIIO::TypeDesc::HALF;
        out.specmod().attribute("compression", "zip");
        out.specmod().attribute("oiio:ColorSpace", "Linear");
    } else {
        out = toDisplaySrgb(linear, kind != FileKind::Jpeg);
        format = OIIO::TypeDesc::UINT8;
        out.specmod().attribute("oiio:ColorSpace", "sRGB");
        if (kind != FileKind::Jpeg) out.specmod().attribute("oiio:UnassociatedAlpha", 1);
        if (kind == FileKind::Jpeg) out.specmod().attribute("CompressionQuality", 95);
    }
    out.set_write_format(format);

    std::string temporary = temporarySibling(target);
    if (!out.write(temporary)) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw std::runtime_error("cannot write '" + path + "': " + out.geterror());
    }
    std::error_code error;
    fs::rename(temporary, target, error);
    if (error) {
        fs::remove(temporary, error);
        throw std::runtime_error("cannot write '" + path + "': " + error.message());
    }
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
