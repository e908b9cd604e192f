// openImageBandReader for programs that link OpenImageIO (ImageBandReader.h).

#include "hdHair/environment/ImageBandReader.h"
#include "hdHair/environment/OiioImageBandReader.h"

namespace hdhair {

std::unique_ptr<ImageBandReader> openImageBandReader(const std::string& path, std::string& why) {
    return openOiioImageBandReader(path, why);
}

}  // namespace hdhair
