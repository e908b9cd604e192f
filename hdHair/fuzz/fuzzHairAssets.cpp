// libFuzzer targets: hair assets as hdhair-convert reads them. Built twice,
// HDHAIR_FUZZ_TRESSFX selecting the TressFX (.tfx 3.0 and 4.0) reader, else
// Cem Yuksel's .hair reader. A malformed file must end in a
// std::runtime_error naming it; anything else is a finding.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hdHair/assets/TressFxReader.h"
#include "hdHair/assets/YukselHairReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<uint8_t> bytes(data, data + size);
    try {
#if HDHAIR_FUZZ_TRESSFX
        hdhair::convert::parseTressFx(bytes, "fuzz.tfx");
#else
        hdhair::convert::parseYukselHair(bytes, "fuzz.hair");
#endif
    } catch (const std::runtime_error&) {
    }
    return 0;
}
