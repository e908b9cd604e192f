#pragma once
// How both readers (the embedded .usda reader and hdhair-record's OpenUSD
// path) word the repair of an authored token or count hdHair does not accept,
// so that one catalogue (docs/hard-cases.md) states one warning for both.

#include <cmath>
#include <string>

namespace hdhair {

// "unknown curve basis 'bogus'; using bezier"
inline std::string unknownTokenRepair(const std::string& kind, const std::string& token, const std::string& fallback) {
    return "unknown " + kind + " '" + token + "'; using " + fallback;
}

// A primvar's elementSize: a positive integer, under a million (a larger one
// declares more values per element than any array could hold sensibly).
inline bool isValidElementSize(double size) { return size >= 1.0 && size == std::floor(size) && size < 1e6; }

inline const char* const kElementSizeRepair = "elementSize must be a positive integer; using 1";

}  // namespace hdhair
