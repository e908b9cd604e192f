// libFuzzer target: .usda text through the embedded reader, composition
// (internal references, variants, list ops) and the scene reader at the
// default and the earliest time. Malformed input must end in an InputError
// or warnings; anything else (a crash, a leak, undefined behaviour, an
// uncaught exception) is a finding (hdHair/fuzz/README.md).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/base/InputError.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/usda/SceneReader.h"
#include "hdHair/usda/Stage.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        // Asset paths resolve against a folder that does not exist, so
        // external references fail cleanly instead of reading the machine.
        std::unique_ptr<hdhair::usda::Stage> stage =
            hdhair::usda::Stage::openFromString(text, "fuzz.usda", "/nonexistent-fuzz-folder");
        for (double time : {std::nan(""), -double(INFINITY), 1.0}) {
            hdhair::Scene scene;
            hdhair::Diagnostics diagnostics;
            hdhair::usda::readScene(*stage, time, scene, diagnostics);
        }
    } catch (const hdhair::InputError&) {
    }
    return 0;
}
