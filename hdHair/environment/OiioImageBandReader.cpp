#include "hdHair/environment/OiioImageBandReader.h"

#include <OpenImageIO/imageio.h>

namespace hdhair {

namespace {

class OiioImageBandReader final : public ImageBandReader {
public:
    explicit OiioImageBandReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input)) {
        const OIIO::ImageSpec& spec = input_->spec();
        layout_.width = spec.width;
        layout_.height = spec.height;
        layout_.depth = spec.depth;
        layout_.channels = spec.nchannels;
        layout_.eightBit = spec.format == OIIO::TypeDesc::UINT8;
        layout_.tileHeight = spec.tile_width > 0 && spec.tile_height > 0 ? spec.tile_height : 0;
    }

    const ImageBandLayout& layout() const override { return layout_; }

    std::string readRows(int y0, int y1, int channels, float* pixels) override {
        const OIIO::ImageSpec& spec = input_->spec();
        const bool ok = layout_.tileHeight > 0
                            ? input_->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y0, spec.y + y1, spec.z,
                                                 spec.z + 1, 0, channels, OIIO::TypeDesc::FLOAT, pixels)
                            : input_->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, channels,
                                                     OIIO::TypeDesc::FLOAT, pixels);
        return ok ? std::string() : input_->geterror();
    }

private:
    std::unique_ptr<OIIO::ImageInput> input_;
    ImageBandLayout layout_;
};

}  // namespace

std::unique_ptr<ImageBandReader> openOiioImageBandReader(const std::string& path, std::string& why) {
    // Unassociated: OpenImageIO would otherwise multiply PNG and TIFF colour
    // by their alpha on read; Storm loads the dome with premultiplyAlpha off.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path, &config);
    if (!input) {
        why = OIIO::geterror();
        return nullptr;
    }
    return std::make_unique<OiioImageBandReader>(std::move(input));
}

}  // namespace hdhair

extern "C" hdhair::ImageBandReader* hdhairOpenImageBandReader(const char* path, std::string* why) {
    return hdhair::openOiioImageBandReader(path, *why).release();
}
