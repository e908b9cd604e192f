#include "hdHair/render/FrameResources.h"

#include "hdHair/gl/GpuMemory.h"

namespace hdhair {

namespace {

bool fits(const std::unique_ptr<gl::RenderTarget>& target, int width, int height,
          const gl::RenderTargetImages& images) {
    return target && target->width() == width && target->height() == height && target->images() == images;
}

}  // namespace

FrameResources::FrameResources() { glGetIntegerv(GL_MAX_SAMPLES, &maxSamples); }

gl::RenderTarget& FrameResources::frameTarget(int width, int height, const gl::RenderTargetImages& images) {
    if (!fits(target_, width, height, images)) {
        const gl::GpuMemoryUse use("frameTarget");
        target_.reset();  // before the new one: a resized frame never holds both
        target_ = std::make_unique<gl::RenderTarget>(width, height, images);
    }
    return *target_;
}

gl::RenderTarget& FrameResources::lightBatchTarget(int width, int height, int samples) {
    // Later light batches add colour only.
    const gl::RenderTargetImages images{false, false, samples};
    if (!fits(batchTarget_, width, height, images)) {
        const gl::GpuMemoryUse use("lightBatchTarget");
        batchTarget_.reset();
        batchTarget_ = std::make_unique<gl::RenderTarget>(width, height, images);
    }
    return *batchTarget_;
}

}  // namespace hdhair
