#pragma once
// Messages quote their input (a prim name, a token, a path). Control bytes
// in a quote would reach the user's terminal as they are -- an escape
// sequence recolouring it, a carriage return hiding the line -- so every
// message hdHair prints shows them as \xNN instead. Bytes from 0x80 up stay
// as they are (UTF-8 names).

#include <cstdio>
#include <string>

namespace hdhair {

inline std::string printableText(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        const unsigned char byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
            out += escaped;
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace hdhair
