#pragma once
// A display transform as GLSL (hdHair/image/DisplayTransform.h writes it;
// gl::DisplayTransformPass runs it): the function hdhairDisplay() and the
// LUT textures and uniforms OpenColorIO's shader needs. Plain data, so the GL
// layer needs nothing of OCIO.

#include <string>
#include <vector>

namespace hdhair {

// The GLSL that OCIO writes for a processor, with the LUTs and uniforms it
// needs (gl::DisplayTransformPass turns them into GL objects).
struct DisplayShader {
    std::string source;  // GLSL 4.0: declarations and vec4 hdhairDisplay(vec4)
    struct Texture {
        std::string samplerName;
        unsigned width = 0, height = 0, depth = 0;  // depth > 0: a 3D LUT (edge length cubed)
        int channels = 3;                           // 1 (red) or 3 (RGB)
        bool linear = true;                         // interpolation
        std::vector<float> values;
    };
    std::vector<Texture> textures;
    struct Uniform {
        enum class Kind { Float, Bool, Float3, FloatArray, IntPairArray };
        std::string name;
        Kind kind = Kind::Float;
        std::vector<double> values;  // one, three, or the array's (pairs: two a pair)
    };
    std::vector<Uniform> uniforms;
};

}  // namespace hdhair
