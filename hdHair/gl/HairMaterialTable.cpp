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
                               const std::vector<MaterialTableLayers>& tables, int width, int height) {
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
    int stacked = 0;
    for (const MaterialTableLayers& table : tables) stacked += table.layers;
    const GLsizei layers = GLsizei(std::max(stacked, 2));
    const GLsizei w = stacked == 0 ? 1 : width, h = stacked == 0 ? 1 : height;
    glTextureStorage3D(tables_.get(), 1, GL_RGBA16F, w, h, layers);
    recordTextureStorage(tables_.get(), GL_RGBA16F, w, h, layers, 0, "hairMaterials");
    GLint first = 0;
    for (const MaterialTableLayers& table : tables) {
        glTextureSubImage3D(tables_.get(), 0, 0, 0, first, width, height, table.layers, GL_RGBA, GL_HALF_FLOAT,
                            table.halfTexels->data());
        first += table.layers;
    }
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
