#include "hdHair/hydra/HydraCamera.h"

#include <cmath>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace hdhair::hydra {

glm::dmat4 matrixFromGf(const double* gfMatrixData) { return glm::make_mat4(gfMatrixData); }

namespace {

bool isUsable(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    double determinant = glm::determinant(m);
    return std::isfinite(determinant) && std::abs(determinant) > 0.0;
}

}  // namespace

CameraView cameraViewFromHydra(const double* worldToView, const double* projection, int width, int height) {
    CameraView view;
    view.view = matrixFromGf(worldToView);
    view.projection = matrixFromGf(projection);
    if (!isUsable(view.view) || !isUsable(view.projection))
        throw std::invalid_argument("the host's camera matrices are not finite and invertible");
    if (width <= 0 || height <= 0) throw std::invalid_argument("the render buffer's data window is empty");
    view.imageWidth = width;
    view.imageHeight = height;
    const glm::dmat4& p = view.projection;
    // An OpenGL orthographic projection keeps w = 1 (its last row is 0 0 0 1).
    view.orthographic = p[3][3] == 1.0 && p[2][3] == 0.0;
    // Recover the clipping planes from the depth rows of GfFrustum's OpenGL
    // matrices (glm indexes [column][row]).
    if (view.orthographic) {
        view.nearClip = (p[3][2] + 1.0) / p[2][2];
        view.farClip = (p[3][2] - 1.0) / p[2][2];
    } else {
        view.nearClip = p[3][2] / (p[2][2] - 1.0);
        view.farClip = p[3][2] / (p[2][2] + 1.0);
    }
    return view;
}

Complexity complexityFromRefineLevel(int refineLevel) {
    if (refineLevel <= 0) return Complexity::Low;
    if (refineLevel == 1) return Complexity::Medium;
    if (refineLevel == 2) return Complexity::High;
    return Complexity::VeryHigh;
}

}  // namespace hdhair::hydra
