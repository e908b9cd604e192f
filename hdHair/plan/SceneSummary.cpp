#include "hdHair/plan/SceneSummary.h"

#include <algorithm>
#include <cmath>

namespace hdhair {

double StrandSummary::meanSegmentsOfAtMost(double length) const {
    double cut = 0.0;
    uint64_t spans = 0;
    for (const std::vector<float>* lengths : spanLengths) {
        for (float span : *lengths) cut += std::isfinite(span) ? std::max(1.0, std::ceil(span / length)) : 1.0;
        spans += lengths->size();
    }
    return spans > 0 ? cut / double(spans) : 0.0;
}

}  // namespace hdhair
