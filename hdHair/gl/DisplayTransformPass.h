#pragma once
// The display transform on the GPU: the frame's colour (pre-multiplied,
// scene-linear) through the GLSL hdHair::DisplayTransform writes (OCIO's
// shader for a display and view, or the sRGB curve), with OCIO's LUTs as
// textures and its uniforms set, into a float image read back for the
// display formats. shaders/displayTransform.frag around the generated
// function; the program is rebuilt only when the shader changes.

#include <string>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/image/DisplayShader.h"

namespace hdhair::gl {

class DisplayTransformPass {
public:
    DisplayTransformPass();

    // Reads `linearColor` (RGBA32F, width x height), writes the display
    // values; `overBlack`: for formats without alpha. Returns RGBA floats,
    // rows from the top down.
    std::vector<float> run(const DisplayShader& shader, GLuint linearColor, int width, int height, bool overBlack);

private:
    void build(const DisplayShader& shader);

    std::string builtSource_;
    Program program_;
    std::vector<Texture> luts_;  // OCIO's LUTs, on units 1, 2, ...
    VertexArray emptyVertexArray_;
    Texture target_;
    Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
};

}  // namespace hdhair::gl
