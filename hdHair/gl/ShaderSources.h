#pragma once
// GLSL sources from shaders/, embedded at build time, with the one piece of
// preprocessing the driver does not do: #include. Shared code (lights,
// Kajiya-Kay, Catmull-Rom weights) lives in shaders/include/ and is written
// with GL_GOOGLE_include_directive so glslangValidator understands it too.

#include <map>
#include <string>

namespace hdhair::gl {

// name (path relative to shaders/, e.g. "strand.frag") -> file contents.
const std::map<std::string, std::string>& embeddedShaderSources();

// Sources that replace embedded files of the same name for one program:
// code written at run time (the display transform OCIO generates).
using ShaderOverrides = std::map<std::string, std::string>;

// The source of a shader with its #include lines replaced by the included
// files (each at most once; `overrides` first) and the include extension
// line removed, as the driver must see it. Throws std::runtime_error naming
// the file for an unknown shader or include.
std::string expandedShaderSource(const std::string& name, const ShaderOverrides& overrides = {});

}  // namespace hdhair::gl
