#pragma once
// The frame's SRBF-convolution tables on the GPU (dome lighting,
// hdHair/plan/DomeLighting.h), as shaders/include/srbfLighting.glsl reads
// them:
// - unit 5: every Marschner table (hdHair/shading/SrbfConvolutionTables.h,
//   GL_RGB16F, 32 × 64 × 512), side by side along x: table k's ψ nodes are
//   x = 32k .. 32k + 31. Along x, not z, because GL guarantees only 2048
//   texels an axis for 3-D textures (llvmpipe's limit too) and a table is
//   32 wide but 512 deep: 64 materials fit, not 4. The lookup clamps ψ to its
//   table's nodes, so tables never blend into each other;
// - unit 6: every Kajiya-Kay table (GL_RG16F, 1 × 64 × 512), side by side
//   along x the same way;
// - unit 7: each table's response to a uniform dome of radiance 1
//   (hdHair/shading/SrbfUniformDome.h), GL_RGB32F, one row of 64 θ_o nodes a
//   table: Marschner tables' rows first, then Kajiya-Kay's.
// A frame without dome lighting uploads 1-texel placeholders.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

// One table's texels as the upload takes them.
struct SrbfTableTexels {
    int width = 1, height = 1, depth = 1;      // one table's size
    const std::vector<uint16_t>* halfTexels = nullptr;  // width × height × depth × channels halves
};

class SrbfTableTextures {
public:
    SrbfTableTextures();
    // Tables of one kind must share their size. `uniformRows`: 64 RGB values
    // a table, Marschner's then Kajiya-Kay's.
    void update(const std::vector<SrbfTableTexels>& marschner, const std::vector<SrbfTableTexels>& kajiyaKay,
                const std::vector<std::vector<glm::vec3>>& uniformRows);
    void bind() const;

private:
    Texture marschner_, kajiyaKay_, uniform_;
};

}  // namespace hdhair::gl
