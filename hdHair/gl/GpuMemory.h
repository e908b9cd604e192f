#pragma once
// The bytes of GL storage hdHair holds, by what it is for ("strandGeometry",
// "frameTarget", "shadowMaps", ...), for --stats: so that a frame's memory can
// be tabled beside peak RSS, and its growth with the segment count checked.
//
// Every buffer made by createBuffer() and every texture given storage by the
// passes is recorded here with its bytes, and forgotten when its handle
// deletes it. The ledger is per thread: GL objects live on the GL thread that
// owns their context (GlRenderThread), one context a thread, so each
// renderer's ledger is its context's. The bytes are what the storage calls
// asked for (width x height x layers x samples x texel size, or the buffer
// size): what a driver allocates for them, give or take its alignment. On
// llvmpipe that memory is process memory, part of the peak RSS; on a GPU it
// is video memory.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include <glad/gl.h>

namespace hdhair::gl {

// Bytes of one texel of a sized internal format hdHair uses; throws
// std::logic_error for one it does not know (a new format must be added).
size_t texelBytes(GLenum internalFormat);

// Records the storage of buffer or texture `name` on this thread's context.
// `use` nullptr: the innermost GpuMemoryUse alive on this thread, else "other".
void recordBufferBytes(GLuint name, size_t bytes, const char* use = nullptr);
// `levels` > 1: a mip chain of 2D levels (each half the last, at least 1
// texel) over the same layers.
void recordTextureStorage(GLuint name, GLenum internalFormat, GLsizei width, GLsizei height, GLsizei depthOrLayers,
                          GLsizei samples, const char* use = nullptr, GLsizei levels = 1);
// A 3-D texture whose `levels` halve along all three sides (at least 1).
void recordVolumeTextureStorage(GLuint name, GLenum internalFormat, GLsizei width, GLsizei height, GLsizei depth,
                                GLsizei levels, const char* use = nullptr);
// Called when the names are deleted (GlObjects' deleters).
void forgetBuffer(GLuint name);
void forgetTexture(GLuint name);

// The recorded bytes of every live buffer and texture on this thread, by use.
std::map<std::string, uint64_t> gpuBytesByUse();

// While alive, buffers and textures recorded on this thread without a use of
// their own are recorded under `use`: for objects made by code that does not
// name them (a pass shared by several resources, a render target), named by
// the code that asks for them.
class GpuMemoryUse {
public:
    explicit GpuMemoryUse(const char* use);
    ~GpuMemoryUse();
    GpuMemoryUse(const GpuMemoryUse&) = delete;
    GpuMemoryUse& operator=(const GpuMemoryUse&) = delete;

private:
    const char* previous_;
};

}  // namespace hdhair::gl
