#include "hdHair/gl/SrbfTableTextures.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {

// Tables of one kind side by side along x; a 1-texel placeholder when none.
Texture tablesTexture(const std::vector<SrbfTableTexels>& tables, GLenum internalFormat, GLenum format) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &name);
    Texture texture(name);
    const SrbfTableTexels one = tables.empty() ? SrbfTableTexels{} : tables.front();
    const GLsizei width = GLsizei(one.width * std::max<size_t>(tables.size(), 1));
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
    if (width > maxSize || one.height > maxSize || one.depth > maxSize)
        throw std::runtime_error("SRBF tables: " + std::to_string(tables.size()) + " tables of " +
                                 std::to_string(one.width) + " x " + std::to_string(one.height) + " x " +
                                 std::to_string(one.depth) + " exceed GL_MAX_3D_TEXTURE_SIZE " +
                                 std::to_string(maxSize));
    glTextureStorage3D(name, 1, internalFormat, width, one.height, one.depth);
    recordTextureStorage(name, internalFormat, width, one.height, one.depth, 0, "srbfTables");
    for (size_t k = 0; k < tables.size(); ++k) {
        if (tables[k].width != one.width || tables[k].height != one.height || tables[k].depth != one.depth)
            throw std::logic_error("SRBF tables of one kind must share their size");
        glTextureSubImage3D(name, 0, GLint(k) * one.width, 0, 0, one.width, one.height, one.depth, format,
                            GL_HALF_FLOAT, tables[k].halfTexels->data());
    }
    if (tables.empty()) {
        const uint16_t zero[3] = {0, 0, 0};
        glTextureSubImage3D(name, 0, 0, 0, 0, 1, 1, 1, format, GL_HALF_FLOAT, zero);
    }
    // What sampleSrbfTable does on the CPU: trilinear between texel centres,
    // clamped at the edges.
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(name, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return texture;
}

}  // namespace

SrbfTableTextures::SrbfTableTextures() { update({}, {}, {}); }

void SrbfTableTextures::update(const std::vector<SrbfTableTexels>& marschner,
                               const std::vector<SrbfTableTexels>& kajiyaKay,
                               const std::vector<std::vector<glm::vec3>>& uniformRows) {
    marschner_ = tablesTexture(marschner, GL_RGB16F, GL_RGB);
    kajiyaKay_ = tablesTexture(kajiyaKay, GL_RG16F, GL_RG);

    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    uniform_ = Texture(name);
    const GLsizei width = uniformRows.empty() ? 1 : GLsizei(uniformRows.front().size());
    const GLsizei height = GLsizei(std::max<size_t>(uniformRows.size(), 1));
    glTextureStorage2D(name, 1, GL_RGB32F, width, height);
    recordTextureStorage(name, GL_RGB32F, width, height, 1, 0, "srbfTables");
    std::vector<glm::vec3> rows(size_t(width) * size_t(height), glm::vec3(0.0f));
    for (size_t r = 0; r < uniformRows.size(); ++r) {
        if (uniformRows[r].size() != size_t(width)) throw std::logic_error("uniform dome rows must share their size");
        std::copy(uniformRows[r].begin(), uniformRows[r].end(), rows.begin() + ptrdiff_t(r * size_t(width)));
    }
    glTextureSubImage2D(name, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rows.data());
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGlError("uploading SRBF tables");
}

void SrbfTableTextures::bind() const {
    glBindTextureUnit(5, marschner_.get());
    glBindTextureUnit(6, kajiyaKay_.get());
    glBindTextureUnit(7, uniform_.get());
}

}  // namespace hdhair::gl
