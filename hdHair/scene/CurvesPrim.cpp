#include "hdHair/scene/CurvesPrim.h"

namespace hdhair {

const char* toString(CurveType type) { return type == CurveType::Linear ? "linear" : "cubic"; }

const char* toString(CurveBasis basis) {
    switch (basis) {
    case CurveBasis::Bezier: return "bezier";
    case CurveBasis::Bspline: return "bspline";
    case CurveBasis::CatmullRom: return "catmullRom";
    }
    return "bezier";
}

const char* toString(CurveWrap wrap) {
    switch (wrap) {
    case CurveWrap::Nonperiodic: return "nonperiodic";
    case CurveWrap::Periodic: return "periodic";
    case CurveWrap::Pinned: return "pinned";
    }
    return "nonperiodic";
}

bool parseCurveType(const std::string& token, CurveType* out) {
    if (token == "linear") *out = CurveType::Linear;
    else if (token == "cubic") *out = CurveType::Cubic;
    else return false;
    return true;
}

bool parseCurveBasis(const std::string& token, CurveBasis* out) {
    if (token == "bezier") *out = CurveBasis::Bezier;
    else if (token == "bspline") *out = CurveBasis::Bspline;
    else if (token == "catmullRom") *out = CurveBasis::CatmullRom;
    else return false;
    return true;
}

bool parseCurveWrap(const std::string& token, CurveWrap* out) {
    if (token == "nonperiodic") *out = CurveWrap::Nonperiodic;
    else if (token == "periodic") *out = CurveWrap::Periodic;
    else if (token == "pinned") *out = CurveWrap::Pinned;
    else return false;
    return true;
}

}  // namespace hdhair
