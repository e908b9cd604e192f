#include "hdHair/gl/GpuMemory.h"

#include <algorithm>

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace hdhair::gl {

namespace {

struct Entry {
    uint64_t bytes = 0;
    const char* use = "other";
};

// Buffers and textures have separate name spaces in GL.
struct Ledger {
    std::unordered_map<GLuint, Entry> buffers, textures;
    const char* currentUse = nullptr;
};

Ledger& ledger() {
    thread_local Ledger perThread;
    return perThread;
}

const char* useOrCurrent(const char* use) {
    if (use) return use;
    return ledger().currentUse ? ledger().currentUse : "other";
}

}  // namespace

size_t texelBytes(GLenum internalFormat) {
    switch (internalFormat) {
    case GL_RGBA32F: return 16;
    case GL_RGB32F: return 12;
    case GL_RGBA16F: return 8;
    case GL_RGB16F: return 6;
    case GL_R32F:
    case GL_R32I:
    case GL_R32UI:
    case GL_DEPTH_COMPONENT32F:
    case GL_RGBA8:
    case GL_RG16F: return 4;
    default:
        throw std::logic_error("GpuMemory: no texel size for GL internal format " + std::to_string(internalFormat));
    }
}

void recordBufferBytes(GLuint name, size_t bytes, const char* use) {
    ledger().buffers[name] = Entry{bytes, useOrCurrent(use)};
}

void recordTextureStorage(GLuint name, GLenum internalFormat, GLsizei width, GLsizei height, GLsizei depthOrLayers,
                          GLsizei samples, const char* use, GLsizei levels) {
    uint64_t texels = 0;
    for (GLsizei level = 0; level < std::max<GLsizei>(levels, 1); ++level)
        texels += uint64_t(std::max(width >> level, 1)) * uint64_t(std::max(height >> level, 1)) *
                  uint64_t(depthOrLayers) * uint64_t(samples > 0 ? samples : 1);
    ledger().textures[name] = Entry{texels * texelBytes(internalFormat), useOrCurrent(use)};
}

void recordVolumeTextureStorage(GLuint name, GLenum internalFormat, GLsizei width, GLsizei height, GLsizei depth,
                                GLsizei levels, const char* use) {
    uint64_t texels = 0;
    for (GLsizei level = 0; level < std::max<GLsizei>(levels, 1); ++level)
        texels += uint64_t(std::max(width >> level, 1)) * uint64_t(std::max(height >> level, 1)) *
                  uint64_t(std::max(depth >> level, 1));
    ledger().textures[name] = Entry{texels * texelBytes(internalFormat), useOrCurrent(use)};
}

void forgetBuffer(GLuint name) { ledger().buffers.erase(name); }

void forgetTexture(GLuint name) { ledger().textures.erase(name); }

std::map<std::string, uint64_t> gpuBytesByUse() {
    std::map<std::string, uint64_t> bytes;
    for (const auto* objects : {&ledger().buffers, &ledger().textures})
        for (const auto& [name, entry] : *objects) bytes[entry.use] += entry.bytes;
    return bytes;
}

GpuMemoryUse::GpuMemoryUse(const char* use) : previous_(ledger().currentUse) { ledger().currentUse = use; }

GpuMemoryUse::~GpuMemoryUse() { ledger().currentUse = previous_; }

}  // namespace hdhair::gl
