#pragma once
// The one exception type for input hdHair cannot use: a malformed .usda file,
// a missing file, a prim that cannot be rendered. what() is a complete,
// user-facing sentence that starts with the location ("file:line:col: ..." or
// "/Prim/path.attribute: ..."), with control bytes quoted from the input
// shown as \xNN (PrintableText.h).

#include <stdexcept>
#include <string>

#include "hdHair/base/PrintableText.h"

namespace hdhair {

class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(printableText(message)) {}
};

}  // namespace hdhair
