#include "hdHair/image/ColorSpaces.h"

namespace hdhair {

glm::mat3 rec709To(RenderingSpace space) {
    if (space == RenderingSpace::LinearRec709) return glm::mat3(1.0f);
    glm::mat3 matrix;
    // glm is column-major: matrix[column][row].
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            matrix[column][row] = float(kRec709ToAp1[size_t(row)][size_t(column)]);
    return matrix;
}

glm::vec3 toRenderingSpace(RenderingSpace space, const glm::vec3& rec709) {
    if (space == RenderingSpace::LinearRec709) return rec709;
    return rec709To(space) * rec709;
}

std::array<float, 8> chromaticitiesOf(RenderingSpace space) {
    if (space == RenderingSpace::AcesCg) return {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f};
    return {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
}

}  // namespace hdhair
