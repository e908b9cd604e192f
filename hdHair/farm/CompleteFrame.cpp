#include "hdHair/farm/CompleteFrame.h"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "hdHair/image/ImageWriter.h"

namespace hdhair::farm {

std::string whyFrameIncomplete(const std::string& path, int width, int height) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return "missing";
    try {
        // Decoding every pixel, not only the header, catches a file cut short.
        const Image image = readImage(path);
        if (image.width != width || image.height != height)
            return fmt::format("{}x{}, not {}x{}", image.width, image.height, width, height);
    } catch (const std::exception& failure) {
        return failure.what();
    }
    return "";
}

}  // namespace hdhair::farm
