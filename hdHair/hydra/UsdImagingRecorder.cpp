#include "hdHair/hydra/UsdImagingRecorder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "pxr/base/gf/half.h"
#include "pxr/base/gf/matrix4d.h"
#include "pxr/base/gf/rect2i.h"
#include "pxr/base/plug/registry.h"
#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/cameraUtil/framing.h"
#include "pxr/imaging/hd/renderBuffer.h"
#include "pxr/imaging/hd/tokens.h"
#include "pxr/usd/usd/stage.h"
#include "pxr/usd/usdGeom/bboxCache.h"
#include "pxr/usd/usdGeom/camera.h"
#include "pxr/usd/usdGeom/metrics.h"
#include "pxr/usd/usdGeom/tokens.h"
#include "pxr/usdImaging/usdImagingGL/engine.h"

#include "hdHair/base/Diagnostics.h"
#include "hdHair/base/InputError.h"
#include "hdHair/hydra/TfDiagnosticCapture.h"
#include "hdHair/hydra/UsdStageChecks.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/FrameMemory.h"
#include "hdHair/scene/SceneValidation.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace hdhair::hydra {
namespace {

UsdTimeCode timeCodeOf(double time) {
    if (std::isnan(time)) return UsdTimeCode::Default();
    if (std::isinf(time)) return UsdTimeCode::EarliestTime();
    return UsdTimeCode(time);
}

GfMatrix4d toGf(const glm::dmat4& m) {
    // glm's column-major memory is GfMatrix4d's row-major memory of the same
    // transform (see HydraCamera.h).
    GfMatrix4d result;
    const double* data = &m[0][0];
    std::copy(data, data + 16, result.data());
    return result;
}

// usdrecord's complexity values for its named levels.
float complexityValue(Complexity complexity) {
    switch (complexity) {
    case Complexity::Low: return 1.0f;
    case Complexity::Medium: return 1.1f;
    case Complexity::High: return 1.2f;
    case Complexity::VeryHigh: return 1.3f;
    }
    return 1.0f;
}

// The color AOV as float RGBA, top row first.
Image readColor(HdRenderBuffer* buffer) {
    if (!buffer) throw std::runtime_error("the renderer produced no color output");
    buffer->Resolve();
    int width = int(buffer->GetWidth()), height = int(buffer->GetHeight());
    HdFormat format = buffer->GetFormat();
    const void* data = buffer->Map();
    Image image(width, height, 4);
    for (int y = 0; y < height; ++y) {
        int row = height - 1 - y;  // Hydra's rows run bottom-up
        for (int x = 0; x < width; ++x) {
            size_t pixel = size_t(row) * size_t(width) + size_t(x);
            for (int c = 0; c < 4; ++c) {
                float value = 0.0f;
                if (format == HdFormatFloat16Vec4) value = float(static_cast<const GfHalf*>(data)[pixel * 4 + size_t(c)]);
                else if (format == HdFormatFloat32Vec4) value = static_cast<const float*>(data)[pixel * 4 + size_t(c)];
                else if (format == HdFormatUNorm8Vec4) value = float(static_cast<const uint8_t*>(data)[pixel * 4 + size_t(c)]) / 255.0f;
                image.at(x, y, c) = value;
            }
        }
    }
    buffer->Unmap();
    return image;
}

// The stage composed from its layers (root layer first), refused for any
// composition error.
UsdStageRefPtr composeStage(const UsdImagingRecordRequest& request, const std::vector<SdfLayerRefPtr>& layers,
                            TfDiagnosticCapture& capture) {
    UsdStageRefPtr stage = UsdStage::Open(layers.front());
    if (!stage) throw InputError(layerOpenFailure(request.stagePath, capture.takeErrors()));
    // Composition errors are errors, as in the embedded reader: a frame
    // with a reference or sublayer silently missing is a wrong picture.
    if (std::string problem = compositionProblem(stage); !problem.empty())
        throw InputError(request.stagePath + ": " + problem);
    return stage;
}

// Each NAME=VALUE setting, checked as the embedded path checks it, given to
// the plugin as a value of its type.
void applyRendererSettings(UsdImagingGLEngine& engine, const std::vector<std::string>& settings) {
    for (const std::string& assignment : settings) {
        RenderSettings check;
        check.setFromAssignment(assignment);  // throws the same one-line reasons as the embedded path
        std::string::size_type equals = assignment.find('=');
        std::string name = assignment.substr(0, equals), text = assignment.substr(equals + 1);
        const SettingDescriptor* descriptor = RenderSettings::find(name);
        VtValue value;
        switch (descriptor->type) {
        case SettingType::Float: value = VtValue(float(check.getFloat(name))); break;
        case SettingType::Int: value = VtValue(check.getInt(name)); break;
        case SettingType::Bool: value = VtValue(check.getBool(name)); break;
        case SettingType::Token: value = VtValue(text); break;
        }
        engine.SetRendererSetting(TfToken(name), value);
    }
}

// The stage's camera at request.camera; returns the image height its
// apertures give.
int useStageCamera(const UsdImagingRecordRequest& request, const UsdStageRefPtr& stage, UsdTimeCode time,
                   UsdImagingGLEngine& engine, UsdImagingRecordResult& result) {
    UsdGeomCamera camera(stage->GetPrimAtPath(SdfPath(request.camera)));
    if (!camera) throw InputError(request.stagePath + ": no camera at '" + request.camera + "'");
    // The embedded reader's checks, worded the same: a lens that cannot
    // be used is an error naming the prim and attribute. Its warnings
    // (a clipping range replaced) are the plugin's to give, once.
    Diagnostics saidByThePlugin;
    const CameraPrim lens = checkedCamera(cameraPrimAt(camera, time), request.stagePath, saidByThePlugin);
    const int height = imageHeightFor(request.imageWidth, lens.horizontalAperture, lens.verticalAperture);
    engine.SetCameraPath(SdfPath(request.camera));
    result.camera = request.camera;
    return height;
}

// hdHair's framing camera, from the stage's bounds as OpenUSD
// computes them for the purposes drawn; returns the image height.
int useFramingCamera(const UsdImagingRecordRequest& request, const UsdStageRefPtr& stage, UsdTimeCode time,
                     UsdImagingGLEngine& engine, UsdImagingRecordResult& result) {
    TfTokenVector purposes = {UsdGeomTokens->default_};
    if (request.renderPurpose) purposes.push_back(UsdGeomTokens->render);
    if (request.proxyPurpose) purposes.push_back(UsdGeomTokens->proxy);
    if (request.guidePurpose) purposes.push_back(UsdGeomTokens->guide);
    UsdGeomBBoxCache bboxCache(time, purposes, true);
    GfRange3d range = bboxCache.ComputeWorldBound(stage->GetPseudoRoot()).ComputeAlignedRange();
    UpAxis up = UsdGeomGetStageUpAxis(stage) == UsdGeomTokens->z ? UpAxis::Z : UpAxis::Y;
    glm::dvec3 low(1.0), high(-1.0);
    if (!range.IsEmpty()) {
        low = glm::dvec3(range.GetMin()[0], range.GetMin()[1], range.GetMin()[2]);
        high = glm::dvec3(range.GetMax()[0], range.GetMax()[1], range.GetMax()[2]);
    }
    CameraView view = frameBounds(low, high, up, request.imageWidth,
                                  request.framing);
    engine.SetCameraState(toGf(view.view), toGf(view.projection));
    result.camera = std::string("framing camera (") + toString(request.framing) + ")";
    return view.imageHeight;
}

UsdImagingGLRenderParams renderParamsFor(const UsdImagingRecordRequest& request, UsdTimeCode time) {
    UsdImagingGLRenderParams renderParams;
    renderParams.frame = time;
    renderParams.complexity = complexityValue(request.complexity);
    renderParams.showRender = request.renderPurpose;
    renderParams.showProxy = request.proxyPurpose;
    renderParams.showGuides = request.guidePurpose;
    renderParams.clearColor = GfVec4f(0.0f);
    renderParams.enableLighting = true;
    return renderParams;
}

// Until convergence, as usdrecord does (10 ms between renders, growing to
// 100): the plugin renders on its own thread, and a slow frame takes as
// long as it takes. It always converges: a frame that fails converges
// with an error, reported through Tf.
void renderUntilConverged(UsdImagingGLEngine& engine, const UsdStageRefPtr& stage,
                          const UsdImagingGLRenderParams& renderParams) {
    std::chrono::milliseconds pause(10);
    for (;;) {
        engine.Render(stage->GetPseudoRoot(), renderParams);
        if (engine.IsConverged()) break;
        std::this_thread::sleep_for(pause);
        pause = std::min(pause + std::chrono::milliseconds(5), std::chrono::milliseconds(100));
    }
}

// A string the plugin put in its render stats; empty when there is none.
std::string statText(const VtDictionary& stats, char const* key) {
    auto found = stats.find(key);
    return found != stats.end() && found->second.IsHolding<std::string>() ? found->second.UncheckedGet<std::string>()
                                                                            : std::string();
}

}  // namespace

UsdImagingRecordResult recordWithUsdImaging(const UsdImagingRecordRequest& request) {
    // Declared first, so that it outlives the engine: the plugin's render
    // thread warns until the engine is gone.
    TfDiagnosticCapture capture([&](const std::string& warning) {
        if (request.warn) request.warn(warning);
    });
    if (!request.pluginPath.empty()) PlugRegistry::GetInstance().RegisterPlugins(request.pluginPath);
    // Every layer opened, checked and bounded before OpenUSD composes the
    // stage; held open so that UsdStage::Open reads none of them again.
    const std::vector<SdfLayerRefPtr> layers =
        openStageLayers(request.stagePath, [&] { return capture.takeErrors(); });
    UsdStageRefPtr stage = composeStage(request, layers, capture);
    capture.takeErrors();  // said as the composition error above, or nothing
    capture.release();
    warnAboutCurveTokens(stage, request.stagePath, [&](const std::string& where, const std::string& message) {
        if (request.warn) request.warn(where + ": " + message);
    });
    UsdTimeCode time = timeCodeOf(request.time);

    UsdImagingGLEngine::Parameters parameters;
    parameters.gpuEnabled = false;  // as usdrecord --disableGpu: hdHair renders in its own context
    UsdImagingGLEngine engine(parameters);
    if (!engine.SetRendererPlugin(TfToken("HdHairRendererPlugin")))
        throw std::runtime_error("the HdHair renderer plugin is not available: not in '" + request.pluginPath +
                                 "' nor on PXR_PLUGINPATH_NAME (set HDHAIR_PLUGIN_RESOURCES to its resources folder)");
    applyRendererSettings(engine, request.settings);

    UsdImagingRecordResult result;
    const int width = request.imageWidth;
    const int height = request.camera.empty() ? useFramingCamera(request, stage, time, engine, result)
                                              : useStageCamera(request, stage, time, engine, result);
    // Before the engine allocates its render buffers: colour (RGBA, 16
    // bytes a pixel at most) and depth (4), and the copy read back here (16).
    {
        RenderSettings frameSettings = RenderSettings::fromAssignments(request.complexity, request.settings);
        checkFrameFitsMemory(width, height, frameSettings, false, false, 36, availableMemory());
    }
    engine.SetRenderBufferSize(GfVec2i(width, height));
    engine.SetFraming(CameraUtilFraming(GfRect2i(GfVec2i(0, 0), width, height)));

    renderUntilConverged(engine, stage, renderParamsFor(request, time));
    VtDictionary stats = engine.GetRenderStats();
    // A frame the plugin could not render converges with cleared buffers
    // (RenderPass.cpp): an error here, never an empty image.
    if (std::string error = statText(stats, "hdHairFrameError");
        !error.empty() || statText(stats, "hdHairShownFrame") == "failed")
        throw std::runtime_error(error.empty() ? "the HdHair plugin could not render the frame" : error);
    for (const std::string& error : capture.takeErrors())
        if (request.warn) request.warn("OpenUSD: " + error);
    result.color = readColor(engine.GetAovRenderBuffer(HdAovTokens->color));
    result.frameStatsJson = statText(stats, "hdHairFrameStats");
    result.plan = statText(stats, "hdHairPlan");
    return result;
}

}  // namespace hdhair::hydra
