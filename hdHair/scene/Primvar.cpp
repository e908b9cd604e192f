#include "hdHair/scene/Primvar.h"

namespace hdhair {

const char* toString(Interpolation interpolation) {
    switch (interpolation) {
    case Interpolation::Constant: return "constant";
    case Interpolation::Uniform: return "uniform";
    case Interpolation::Varying: return "varying";
    case Interpolation::Vertex: return "vertex";
    case Interpolation::FaceVarying: return "faceVarying";
    }
    return "constant";
}

bool parseInterpolation(const std::string& token, Interpolation* out) {
    if (token == "constant") *out = Interpolation::Constant;
    else if (token == "uniform") *out = Interpolation::Uniform;
    else if (token == "varying") *out = Interpolation::Varying;
    else if (token == "vertex") *out = Interpolation::Vertex;
    else if (token == "faceVarying") *out = Interpolation::FaceVarying;
    else return false;
    return true;
}

}  // namespace hdhair
