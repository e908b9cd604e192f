#pragma once
// What hdhair-bench --accuracy measures: each approximation hdHair makes, as
// a ladder of its setting's values from the cheapest toward the reference,
// every other setting at its default, and the four quality presets. A step
// list names every setting it changes, so the matrix does not depend on
// where the defaults lie; the default's step is marked.

#include <string>
#include <vector>

namespace hdhair::accuracy {

// What the error must do along an approximation's ladder (the --quick
// check, AccuracyChecks.h).
enum class ErrorTrend {
    Falls,  // each step's error at most the previous one's, within the noise allowance
    Flat,   // not an approximation: every step's error the same, within the allowance
};
const char* toString(ErrorTrend trend);

struct Step {
    std::string label;                  // "256 bins", "0.12 px"
    std::vector<std::string> settings;  // NAME=VALUE over the approximation's base
    bool isDefault = false;             // the setting at its default value (over the base)
};

struct Approximation {
    std::string name;                // "sortBins"
    std::string trades;              // one line: what it trades, for the report
    std::vector<std::string> base;   // settings under every step and its reference (shadingModel=marschner)
    std::vector<Step> steps;         // cheapest first, toward the reference
    ErrorTrend trend = ErrorTrend::Falls;
    // Falls is checked only up to the default's step when the error beyond
    // it is known not to fall (shadowMapResolution: README's shadow table).
    bool checkedBeyondDefault = true;
    // False for sampling approximations (MSAA, supersampling): their own
    // error is their error at one sample a pixel, since at the reference's
    // samples per pixel they would measure nothing of their own.
    bool ownErrorAtReferenceSampling = true;
};

// The full matrix, or (quick) the same approximations with shorter ladders
// for CI: the cheap end, the default and the step toward the reference.
std::vector<Approximation> accuracyMatrix(bool quick);

// The presets as steps ("quality=preview", ...): the report labels them on
// the plots and checks they lie on the front.
std::vector<Step> presetSteps();

}  // namespace hdhair::accuracy
