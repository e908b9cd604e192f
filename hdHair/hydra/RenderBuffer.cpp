#include "hdHair/hydra/RenderBuffer.h"

#include <cstring>

#include "pxr/base/gf/half.h"
#include "pxr/base/gf/vec3i.h"
#include "pxr/base/gf/vec4f.h"
#include "pxr/base/tf/diagnostic.h"

#include "hdHair/hydra/DeferredIds.h"

PXR_NAMESPACE_OPEN_SCOPE

HdHairRenderBuffer::HdHairRenderBuffer(SdfPath const& id) : HdRenderBuffer(id) {}

bool HdHairRenderBuffer::Allocate(GfVec3i const& dimensions, HdFormat format, bool multiSampled) {
    _Deallocate();
    if (dimensions[2] != 1) {
        TF_WARN("hdHair: render buffer %s: 3D buffers are not supported (depth %d)", GetId().GetText(),
                dimensions[2]);
        return false;
    }
    _width = unsigned(std::max(dimensions[0], 0));
    _height = unsigned(std::max(dimensions[1], 0));
    _format = format;
    // MSAA, where hdHair uses it, happens inside the engine: the buffer
    // only holds resolved pixels.
    _multiSampled = multiSampled;
    _data.assign(size_t(_width) * _height * HdDataSizeOfFormat(format), 0);
    _converged.store(false);
    return true;
}

void HdHairRenderBuffer::_Deallocate() {
    SetDeferredIds(nullptr, TfToken(), {});
    _width = _height = 0;
    _format = HdFormatInvalid;
    _data.clear();
    _data.shrink_to_fit();
    _mappers.store(0);
    _converged.store(false);
}

void* HdHairRenderBuffer::Map() {
    Resolve();
    ++_mappers;
    return _data.data();
}

void HdHairRenderBuffer::Resolve() {
    std::shared_ptr<DeferredIds> deferred;
    {
        std::lock_guard<std::mutex> lock(_deferredMutex);
        deferred = std::move(_deferred);
        _deferred.reset();
    }
    if (!deferred) return;
    // Left as cleared (-1: nothing) when the ids could not be rendered.
    hdhair::hydra::writeIdsToBuffer(deferred->Ids(_deferredAov), _deferredWindow, int(_width), int(_height),
                                    _data.data());
}

void HdHairRenderBuffer::SetDeferredIds(std::shared_ptr<DeferredIds> deferred, TfToken const& aov,
                                        hdhair::hydra::DataWindow const& window) {
    std::lock_guard<std::mutex> lock(_deferredMutex);
    _deferred = std::move(deferred);
    _deferredAov = aov;
    _deferredWindow = window;
}

void HdHairRenderBuffer::Unmap() { --_mappers; }

bool HdHairRenderBuffer::GetWritableFormat(hdhair::hydra::BufferFormat* format) const {
    using hdhair::hydra::BufferFormat;
    switch (_format) {
    case HdFormatFloat16Vec4: *format = BufferFormat::Float16Vec4; return true;
    case HdFormatFloat32Vec4: *format = BufferFormat::Float32Vec4; return true;
    case HdFormatUNorm8Vec4: *format = BufferFormat::UNorm8Vec4; return true;
    case HdFormatFloat32: *format = BufferFormat::Float32; return true;
    case HdFormatInt32: *format = BufferFormat::Int32; return true;
    default: return false;
    }
}

void HdHairRenderBuffer::Clear(VtValue const& clearValue) {
    if (clearValue.IsEmpty() || _data.empty()) return;
    size_t pixelSize = HdDataSizeOfFormat(_format);
    std::vector<uint8_t> pixel(pixelSize, 0);
    if (_format == HdFormatFloat16Vec4 || _format == HdFormatFloat32Vec4 || _format == HdFormatUNorm8Vec4) {
        GfVec4f color = clearValue.IsHolding<GfVec4f>() ? clearValue.UncheckedGet<GfVec4f>() : GfVec4f(0.0f);
        for (int c = 0; c < 4; ++c) {
            if (_format == HdFormatFloat16Vec4) {
                GfHalf h(color[c]);
                std::memcpy(&pixel[size_t(c) * 2], &h, 2);
            } else if (_format == HdFormatFloat32Vec4) {
                std::memcpy(&pixel[size_t(c) * 4], &color[c], 4);
            } else {
                pixel[size_t(c)] = uint8_t(std::clamp(color[c], 0.0f, 1.0f) * 255.0f + 0.5f);
            }
        }
    } else if (_format == HdFormatFloat32) {
        float value = clearValue.IsHolding<float>() ? clearValue.UncheckedGet<float>()
                      : clearValue.IsHolding<double>() ? float(clearValue.UncheckedGet<double>())
                                                        : 1.0f;
        std::memcpy(pixel.data(), &value, 4);
    } else if (_format == HdFormatInt32) {
        int32_t value = clearValue.IsHolding<int>() ? clearValue.UncheckedGet<int>() : -1;
        std::memcpy(pixel.data(), &value, 4);
    } else {
        return;
    }
    for (size_t offset = 0; offset < _data.size(); offset += pixelSize)
        std::memcpy(&_data[offset], pixel.data(), pixelSize);
}

PXR_NAMESPACE_CLOSE_SCOPE
