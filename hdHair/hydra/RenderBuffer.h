#pragma once
// HdHairRenderBuffer: an AOV's pixels in CPU memory, tightly packed with row
// 0 at the bottom (what hosts read through Map(); see RenderBufferWriting.h).
// Only the render pass writes it, on the host's thread, and only with whole
// images (RenderPass.h): unconverged from the moment a new view is asked for,
// through any previews, until the full frame is in. An id buffer may be left
// to a DeferredIds, which writes its image on the first Resolve() or Map().

#include <atomic>
#include <memory>
#include <cstdint>
#include <mutex>
#include <vector>

#include "pxr/base/tf/token.h"
#include "pxr/imaging/hd/renderBuffer.h"

#include "hdHair/hydra/RenderBufferWriting.h"

PXR_NAMESPACE_OPEN_SCOPE

class DeferredIds;

class HdHairRenderBuffer final : public HdRenderBuffer {
public:
    explicit HdHairRenderBuffer(SdfPath const& id);
    ~HdHairRenderBuffer() override = default;

    bool Allocate(GfVec3i const& dimensions, HdFormat format, bool multiSampled) override;
    unsigned int GetWidth() const override { return _width; }
    unsigned int GetHeight() const override { return _height; }
    unsigned int GetDepth() const override { return 1; }
    HdFormat GetFormat() const override { return _format; }
    bool IsMultiSampled() const override { return _multiSampled; }
    void* Map() override;  // resolves first
    void Unmap() override;
    bool IsMapped() const override { return _mappers.load() > 0; }
    // Writes the deferred ids, if any; otherwise the render pass has already
    // written final pixels.
    void Resolve() override;
    bool IsConverged() const override { return _converged.load(); }

    // For the render pass.
    void SetConverged(bool converged) { _converged.store(converged); }
    // Fills every pixel with `clearValue` (a VtValue of the buffer's type).
    void Clear(VtValue const& clearValue);
    // The engine's format for this buffer, or false when hdHair cannot write it.
    bool GetWritableFormat(hdhair::hydra::BufferFormat* format) const;
    uint8_t* GetData() { return _data.data(); }
    // Leaves this buffer's pixels (the id AOV `aov`, at `window`) to
    // `deferred`, written on the next Resolve() or Map(); null: none.
    void SetDeferredIds(std::shared_ptr<DeferredIds> deferred, TfToken const& aov,
                        hdhair::hydra::DataWindow const& window);

protected:
    void _Deallocate() override;

private:
    unsigned int _width = 0, _height = 0;
    HdFormat _format = HdFormatInvalid;
    bool _multiSampled = false;
    std::vector<uint8_t> _data;
    std::atomic<int> _mappers{0};
    std::atomic<bool> _converged{false};
    std::mutex _deferredMutex;
    std::shared_ptr<DeferredIds> _deferred;
    TfToken _deferredAov;
    hdhair::hydra::DataWindow _deferredWindow;
};

PXR_NAMESPACE_CLOSE_SCOPE
