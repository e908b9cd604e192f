#include "hdHair/render/FrameResources.h"

namespace hdhair {

namespace {

bool fits(const std::unique_ptr<gl::RenderTarget>& target, int width, int height,
          const gl::RenderTargetImages& images) {
    return target && target->width() == width && target->height() == height && target->images() == images;
}

}  // namespace

FrameResources::FrameResources() { glGetIntegerv(GL_MAX_SAMPLES, &maxSamples); }

gl::RenderTarget& FrameResources::frameTarget(int width, int height, const gl::RenderTargetImages& images) {
    if (!fits(target_, width, height, images)) target_ = std::make_unique<gl::RenderTarget>(width, height, images);
    return *target_;
}

gl::RenderTarget& FrameResources::lightBatchTarget(int width, int height, int samples) {
    // Later light batches add colour only.
    const gl::RenderTargetImages images{false, false, samples};
    if (!fits(batchTarget_, width, height, images))
        batchTarget_ = std::make_unique<gl::RenderTarget>(width, height, images);
    return *batchTarget_;
}

}  // namespace hdhair
