#pragma once
// HDHAIR_UPDATE_BASELINES, read the same way by every test that keeps
// baselines: "1" rewrites them; unset, empty or "0" compares against them;
// any other value is an error, so that "true" or "yes" is not silently taken
// as "compare". A test that rewrites a baseline then fails (rewriteDone):
// that run checked nothing, and must never report a pass.

#include <cstdlib>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace hdhair::testenv {

inline bool updatingBaselines() {
    const char* value = std::getenv("HDHAIR_UPDATE_BASELINES");
    if (!value || !*value || std::string(value) == "0") return false;
    if (std::string(value) == "1") return true;
    throw std::invalid_argument("HDHAIR_UPDATE_BASELINES='" + std::string(value) +
                                "': only 1 rewrites the baselines (unset, empty or 0 compares)");
}

// Fails the current test after its baselines were rewritten.
#define HDHAIR_BASELINES_REWRITTEN(what)                                                                         \
    FAIL() << "baselines rewritten (" << (what)                                                                   \
           << "): this run compared nothing; review them in git and run again without HDHAIR_UPDATE_BASELINES"

}  // namespace hdhair::testenv
