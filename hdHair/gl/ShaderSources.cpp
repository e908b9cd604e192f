#include "hdHair/gl/ShaderSources.h"

#include <set>
#include <sstream>
#include <stdexcept>

namespace hdhair::gl {
namespace {

const std::string& sourceOf(const std::string& name, const std::string& includedFrom,
                            const ShaderOverrides& overrides) {
    auto overridden = overrides.find(name);
    if (overridden != overrides.end()) return overridden->second;
    const auto& sources = embeddedShaderSources();
    auto it = sources.find(name);
    if (it == sources.end())
        throw std::runtime_error(includedFrom.empty()
                                     ? "unknown shader '" + name + "'"
                                     : includedFrom + ": cannot include unknown shader '" + name + "'");
    return it->second;
}

void expandInto(const std::string& name, const std::string& includedFrom, const ShaderOverrides& overrides,
                std::set<std::string>& included, std::string& out) {
    if (!included.insert(name).second) return;
    std::istringstream lines(sourceOf(name, includedFrom, overrides));
    std::string line;
    int lineNumber = 0;
    while (std::getline(lines, line)) {
        ++lineNumber;
        std::string::size_type first = line.find_first_not_of(" \t");
        std::string trimmed = first == std::string::npos ? "" : line.substr(first);
        if (trimmed.rfind("#extension GL_GOOGLE_include_directive", 0) == 0) continue;
        if (trimmed.rfind("#include", 0) == 0) {
            std::string::size_type open = trimmed.find('"');
            std::string::size_type close = trimmed.find('"', open + 1);
            if (open == std::string::npos || close == std::string::npos)
                throw std::runtime_error(name + ":" + std::to_string(lineNumber) +
                                         ": malformed #include");
            expandInto(trimmed.substr(open + 1, close - open - 1), name + ":" + std::to_string(lineNumber),
                       overrides, included, out);
            continue;
        }
        out += line;
        out += '\n';
    }
}

}  // namespace

std::string expandedShaderSource(const std::string& name, const ShaderOverrides& overrides) {
    std::set<std::string> included;
    std::string out;
    expandInto(name, "", overrides, included, out);
    return out;
}

}  // namespace hdhair::gl
