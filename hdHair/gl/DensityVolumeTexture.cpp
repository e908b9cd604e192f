#include "hdHair/gl/DensityVolumeTexture.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {

constexpr GLuint kDensityVolumeUnit = 8;  // densityVolume.glsl's binding

// A full mip chain: down to one voxel along the longest side.
GLsizei densityMipLevels(const glm::ivec3& dims) {
    GLsizei levels = 1;
    for (int longest = std::max({dims.x, dims.y, dims.z}); longest > 1; longest >>= 1) ++levels;
    return levels;
}

}  // namespace

DensityVolumeTexture::DensityVolumeTexture() { update(DensityGrid()); }

void DensityVolumeTexture::update(const DensityGrid& grid) {
    const bool empty = grid.shape.empty();
    const glm::ivec3 dims = empty ? glm::ivec3(1) : grid.shape.dims;
    if (dims != dims_ || !texture_) {
        GLint maxSize = 0;
        glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
        if (dims.x > maxSize || dims.y > maxSize || dims.z > maxSize)
            throw std::runtime_error("the hair density volume's " + std::to_string(dims.x) + " x " +
                                     std::to_string(dims.y) + " x " + std::to_string(dims.z) +
                                     " voxels exceed GL_MAX_3D_TEXTURE_SIZE " + std::to_string(maxSize));
        GLuint name = 0;
        glCreateTextures(GL_TEXTURE_3D, 1, &name);
        texture_ = Texture(name);
        levels_ = densityMipLevels(dims);
        glTextureStorage3D(name, levels_, GL_R32F, dims.x, dims.y, dims.z);
        recordVolumeTextureStorage(name, GL_R32F, dims.x, dims.y, dims.z, levels_, "densityVolume");
        glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(name, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        dims_ = dims;
    }
    const float zero = 0.0f;
    glTextureSubImage3D(texture_.get(), 0, 0, 0, 0, dims.x, dims.y, dims.z, GL_RED, GL_FLOAT,
                        empty ? &zero : grid.extinction.data());
    // The mip chain from the CPU (halvedDensity): llvmpipe's
    // glGenerateMipmap of a 3-D texture costs a frame's worth of shader
    // compilation the first time, and this is the same box filter.
    std::vector<float> level = empty ? std::vector<float>() : grid.extinction;
    glm::ivec3 levelDims = dims;
    for (GLsizei mip = 1; mip < levels_; ++mip) {
        glm::ivec3 halvedDims;
        level = halvedDensity(level, levelDims, halvedDims);
        levelDims = halvedDims;
        glTextureSubImage3D(texture_.get(), mip, 0, 0, 0, levelDims.x, levelDims.y, levelDims.z, GL_RED, GL_FLOAT,
                            level.data());
    }
}

void DensityVolumeTexture::release() {
    if (dims_ != glm::ivec3(1)) update(DensityGrid());
}

void DensityVolumeTexture::bind() const { glBindTextureUnit(kDensityVolumeUnit, texture_.get()); }

}  // namespace hdhair::gl
