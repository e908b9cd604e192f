#pragma once
// ImageBandReader through OpenImageIO: the one decoder both ways of reaching
// it (ImageBandReader.h) call.

#include "hdHair/environment/ImageBandReader.h"

namespace hdhair {

std::unique_ptr<ImageBandReader> openOiioImageBandReader(const std::string& path, std::string& why);

}  // namespace hdhair

// The module's entry point, looked up by name with dlsym
// (LoadedImageBandReader.cpp): a plain C symbol, so no C++ name mangling
// stands between the plugin and the module. Returns an owned reader, or null
// with *why set.
extern "C" hdhair::ImageBandReader* hdhairOpenImageBandReader(const char* path, std::string* why);
