#include "hdHair/shading/ColorTemperature.h"

#include <algorithm>
#include <cmath>

namespace hdhair {

namespace {

// One asymmetric Gaussian lobe: width `below` left of the peak, `above` right of it.
double lobe(double lambda, double peak, double below, double above) {
    double t = (lambda - peak) / (lambda < peak ? below : above);
    return std::exp(-0.5 * t * t);
}

// CIE 1931 2° colour matching functions, Wyman, Sloan and Shirley's fit.
void matchingFunctions(double lambda, double* x, double* y, double* z) {
    *x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
         0.065 * lobe(lambda, 501.1, 20.4, 26.2);
    *y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
    *z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
}

// Spectral radiance of a blackbody up to a constant factor (which the
// normalisation removes): λ⁻⁵ / (exp(c₂ / λT) − 1), λ in nm.
double planck(double lambdaNm, double kelvin) {
    constexpr double kSecondRadiationConstant = 1.4387769e7;  // c₂ = hc/k in nm·K
    return 1.0 / (std::pow(lambdaNm, 5.0) * std::expm1(kSecondRadiationConstant / (lambdaNm * kelvin)));
}

}  // namespace

glm::vec3 blackbodyColor(float kelvin) {
    double t = std::isnan(kelvin) ? 6500.0
                                  : double(std::clamp(kelvin, kMinColorTemperature, kMaxColorTemperature));
    // Riemann sum over 5 nm steps: the integrands are smooth, and 1 nm steps
    // change the chromaticity by less than 1e-4.
    double sumX = 0.0, sumY = 0.0, sumZ = 0.0;
    for (int lambda = 360; lambda <= 830; lambda += 5) {
        double x, y, z;
        matchingFunctions(lambda, &x, &y, &z);
        double radiance = planck(lambda, t);
        sumX += radiance * x;
        sumY += radiance * y;
        sumZ += radiance * z;
    }
    double X = sumX / sumY, Y = 1.0, Z = sumZ / sumY;
    // XYZ to linear Rec.709 / sRGB primaries, D65 white (IEC 61966-2-1).
    double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
    double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
    double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
    r = std::max(r, 0.0);
    g = std::max(g, 0.0);
    b = std::max(b, 0.0);
    double luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    return glm::vec3(float(r / luminance), float(g / luminance), float(b / luminance));
}

}  // namespace hdhair
