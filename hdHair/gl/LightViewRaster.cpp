#include "hdHair/gl/LightViewRaster.h"

#include <algorithm>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {
// shaders/lightViewDepth.comp and lightViewOpacity.comp: workgroup size and
// uniform locations; lightViewLayers.comp's workgroup is 8 x 8 texels.
constexpr GLuint kSpanWorkgroup = 32, kLayerWorkgroup = 8;
constexpr GLint kRangeFirst = 0, kRangeCount = 1;
// Bindings: the depth layer as an R32UI image, the opacity layers as an
// RGBA16F image, the per-layer sums as a storage buffer.
constexpr GLuint kDepthImage = 2, kOpacityImage = 3, kLayerSums = 11;
// Spans a dispatch: GL guarantees 65535 workgroups in x.
constexpr uint64_t kDispatchSpans = uint64_t(65535) * kSpanWorkgroup;
}  // namespace

LightViewRaster::LightViewRaster()
    : depthPrograms_({"lightViewDepth.comp"}),
      opacityPrograms_({"lightViewOpacity.comp"}),
      layerPrograms_({"lightViewLayers.comp"}) {}

size_t LightViewRaster::layerSumBytes(int resolution, int layers) {
    return size_t(resolution) * size_t(resolution) * size_t(std::max(layers, 1)) * sizeof(float);
}

void LightViewRaster::dispatchSpans(const Program& program, const std::vector<SegmentRange>& ranges) {
    glUseProgram(program.get());
    for (const SegmentRange& range : joinedRanges(ranges))
        for (uint64_t first = range.first; first < range.first + range.count; first += kDispatchSpans) {
            const uint64_t count = std::min(range.first + range.count - first, kDispatchSpans);
            glProgramUniform1ui(program.get(), kRangeFirst, GLuint(first));
            glProgramUniform1ui(program.get(), kRangeCount, GLuint(count));
            glDispatchCompute(GLuint((count + kSpanWorkgroup - 1) / kSpanWorkgroup), 1, 1);
        }
}

void LightViewRaster::renderDepth(ShadowMapStorage& storage, const StrandGeometry& geometry,
                                  const std::vector<SegmentRange>& ranges, const ShadowUniforms& light) {
    storage.clearHairDepth(int(light.lightMap[0].x));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    geometry.bind();
    // R32F and R32UI are compatible by size: the minimum is taken on the bits.
    glBindImageTexture(kDepthImage, storage.hairDepths(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    dispatchSpans(depthPrograms_.get(ShadingFeatures::all()), ranges);
    glBindImageTexture(kDepthImage, 0, 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    glUseProgram(0);
    // The opacity pass and the camera's lookups read the depths as a texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    checkGlError("rasterising a shadow depth map in compute");
}

void LightViewRaster::renderOpacity(ShadowMapStorage& storage, const StrandGeometry& geometry,
                                    const std::vector<SegmentRange>& ranges, const ShadowUniforms& light) {
    const int layers = light.mode.y;
    const int resolution = storage.resolution();
    const size_t bytes = layerSumBytes(resolution, layers);
    if (!layerSums_ || layerSumCapacity_ < bytes) {
        layerSums_ = createBuffer(nullptr, bytes, 0, "shadowMaps");
        layerSumCapacity_ = bytes;
        const uint32_t zero = 0;  // lightViewLayers.comp leaves them zero after each map
        glClearNamedBufferData(layerSums_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    const ShadingFeatures features = ShadingFeatures::all().setShadowLayers(layers);
    geometry.bind();
    storage.bindForLookup();  // the nearest depths, drawn by renderDepth
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLayerSums, layerSums_.get());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    dispatchSpans(opacityPrograms_.get(features), ranges);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindImageTexture(kOpacityImage, storage.opacityLayers(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUseProgram(layerPrograms_.get(features).get());
    const GLuint groups = GLuint((resolution + int(kLayerWorkgroup) - 1) / int(kLayerWorkgroup));
    glDispatchCompute(groups, groups, 1);
    glBindImageTexture(kOpacityImage, 0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glUseProgram(0);
    // Read as textures by the camera's lookups (and averaged into mipmaps);
    // the sums are read again by the next map.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);
    checkGlError("rasterising deep opacity layers in compute");
}

}  // namespace hdhair::gl
