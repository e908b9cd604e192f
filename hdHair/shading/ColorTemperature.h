#pragma once
// The colour of a blackbody, as UsdLux's inputs:colorTemperature uses it
// (UsdLuxBlackbodyTemperatureAsRgb): linear Rec.709 RGB, scaled so that its
// luminance 0.2126 R + 0.7152 G + 0.0722 B is 1, so that enabling a colour
// temperature changes a light's hue but not its brightness.
//
// Computed from first principles rather than a table: Planck's law
// integrated against the CIE 1931 2° colour matching functions (the
// multi-lobe Gaussian fit of Wyman, Sloan and Shirley, JCGT 2(2), 2013)
// from 360 to 830 nm, converted from XYZ to linear Rec.709 (D65 white; no
// chromatic adaptation, so 6500 K is close to but not exactly white:
// about (1.04, 0.98, 1.03)). Colours outside the Rec.709 gamut (below
// about 1900 K the blue component is negative) are clamped to zero before
// the luminance is normalised. The result agrees with OpenUSD 24.08's
// fitted table within about 2% per channel from 1000 K to 10000 K.
//
// Temperatures are clamped to [1000, 10000] K, the range UsdLux's mapping
// covers; NaN counts as 6500 K.

#include <glm/vec3.hpp>

namespace hdhair {

constexpr float kMinColorTemperature = 1000.0f;   // K
constexpr float kMaxColorTemperature = 10000.0f;  // K

glm::vec3 blackbodyColor(float kelvin);

}  // namespace hdhair
