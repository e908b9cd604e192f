#pragma once
// From the renderer's scene-linear colour to the code values a display
// shows, as usdrecord's --colorCorrectionMode chooses:
//  - disabled: values as they are;
//  - sRGB: the sRGB curve (IEC 61966-2-1) on linear Rec.709 (an ACEScg
//    image is first brought to Rec.709 primaries);
//  - openColorIO: an OCIO display/view (and optional look) of a config:
//    --ocioConfig, else $OCIO, else hdHair's own (hdHair/image/ocio/config.ocio).
// Scene-linear outputs (EXR) never go through it. Built once; the CPU path
// applies it here, the GPU path (gl::DisplayTransformPass) runs the shader
// OCIO writes for the same processor.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/base/TokenTable.h"
#include "hdHair/image/ColorSpaces.h"
#include "hdHair/image/DisplayShader.h"

namespace hdhair {

enum class ColorCorrectionMode { Disabled, SRGB, OpenColorIO };
template <>
struct TokenTable<ColorCorrectionMode> {
    static constexpr std::array<TokenName<ColorCorrectionMode>, 3> names{{
         {ColorCorrectionMode::Disabled, "disabled"},
         {ColorCorrectionMode::SRGB, "sRGB"},
         {ColorCorrectionMode::OpenColorIO, "openColorIO"}}};
};

struct DisplayTransformOptions {
    ColorCorrectionMode mode = ColorCorrectionMode::SRGB;
    std::string config;        // "" : $OCIO, else the shipped config
    std::string display;       // "" : the config's default display
    std::string view;          // "" : the display's default view
    std::string look;          // "" : the view's own looks (none in hdHair's config)
    std::string colorSpace;    // the image's colour space: "" is the rendering space
    std::string renderingSpace = kLinearRec709;
};

class DisplayTransform {
public:
    // Throws std::invalid_argument with one line: the config cannot be read,
    // or a display, view, look or colour space it does not have (the valid
    // names listed).
    static DisplayTransform create(const DisplayTransformOptions& options);

    ColorCorrectionMode mode() const { return mode_; }
    // Applies the transform to `pixels` RGBA floats in place; alpha is
    // untouched, RGB must be un-premultiplied (or over black, for formats
    // without alpha).
    void apply(float* rgba, size_t pixels) const;
    // The same transform for the GPU (OCIO's shader path; the sRGB and
    // disabled modes are written here as GLSL too).
    DisplayShader shader() const;
    // What was chosen, for --stats: mode, config, display, view, look, colour space.
    nlohmann::json describe() const;
    std::string summary() const;  // one line, for --verbose

    // The config hdHair ships: share/hdhair/ocio/config.ocio beside the
    // executable's folder, in the build and install trees alike.
    static std::string shippedConfigPath();

private:
    struct Ocio;
    ColorCorrectionMode mode_ = ColorCorrectionMode::SRGB;
    bool fromAcesCg_ = false;  // sRGB mode: AP1 primaries to Rec.709 first
    std::string configPath_, display_, view_, look_, colorSpace_;
    std::shared_ptr<const Ocio> ocio_;
};

}  // namespace hdhair
