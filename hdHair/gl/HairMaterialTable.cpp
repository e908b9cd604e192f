#include "hdHair/gl/HairMaterialTable.h"

#include <algorithm>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

HairMaterialTable::HairMaterialTable() {
    // Shaders always declare the tables: start with two empty layers.
    update({GpuHairMaterial{}}, {}, {}, 1, 1);
}

void HairMaterialTable::update(const std::vector<GpuHairMaterial>& materials,
                               const std::vector<glm::vec4>& parameterPoints,
                               const std::vector<const std::vector<uint16_t>*>& tableTexels, int width, int height) {
    size_t count = std::max<size_t>(materials.size(), 1);
    if (count > materialCapacity_) {
        materialCapacity_ = count;
        materials_ = createBuffer(nullptr, count * sizeof(GpuHairMaterial), GL_DYNAMIC_STORAGE_BIT, "hairMaterials");
    }
    if (!materials.empty())
        glNamedBufferSubData(materials_.get(), 0, GLsizeiptr(materials.size() * sizeof(GpuHairMaterial)),
                             materials.data());

    // Always a buffer at binding 9, even when no prim has per-point parameters.
    size_t points = std::max<size_t>(parameterPoints.size(), 2);
    if (points > parameterPointCapacity_) {
        parameterPointCapacity_ = points;
        parameterPoints_ =
            createBuffer(nullptr, points * sizeof(glm::vec4), GL_DYNAMIC_STORAGE_BIT, "hairMaterials");
    }
    if (!parameterPoints.empty())
        glNamedBufferSubData(parameterPoints_.get(), 0, GLsizeiptr(parameterPoints.size() * sizeof(glm::vec4)),
                             parameterPoints.data());

    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &name);
    tables_ = Texture(name);
    GLsizei layers = GLsizei(std::max<size_t>(2 * tableTexels.size(), 2));
    glTextureStorage3D(tables_.get(), 1, GL_RGBA16F, tableTexels.empty() ? 1 : width,
                       tableTexels.empty() ? 1 : height, layers);
    recordTextureStorage(tables_.get(), GL_RGBA16F, tableTexels.empty() ? 1 : width, tableTexels.empty() ? 1 : height,
                         layers, 0, "hairMaterials");
    for (size_t k = 0; k < tableTexels.size(); ++k)
        glTextureSubImage3D(tables_.get(), 0, 0, 0, GLint(2 * k), width, height, 2, GL_RGBA, GL_HALF_FLOAT,
                            tableTexels[k]->data());
    // Bilinear between texel centres, clamped at the edges: what the CPU
    // lookup (sampleMarschnerTables) does.
    glTextureParameteri(tables_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tables_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tables_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tables_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkGlError("uploading hair materials");
}

void HairMaterialTable::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, materials_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, parameterPoints_.get());
    glBindTextureUnit(1, tables_.get());
}

}  // namespace hdhair::gl
