// libFuzzer target: primvar resolution and curve preparation on curves prims
// built from the fuzzer's bytes: any type, basis and wrap, vertex counts
// (negative, zero, huge), points with NaN and infinities, and primvars of
// every interpolation with indices and element sizes. prepareCurves never
// throws for bad data (it repairs and warns): any exception or sanitizer
// report is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include <fuzzer/FuzzedDataProvider.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/scene/CurvesPrim.h"

namespace {

float anyFloat(FuzzedDataProvider& fuzz) {
    switch (fuzz.ConsumeIntegralInRange(0, 7)) {
    case 0: return std::numeric_limits<float>::quiet_NaN();
    case 1: return std::numeric_limits<float>::infinity();
    case 2: return 1e38f;
    case 3: return 0.0f;
    default: return fuzz.ConsumeFloatingPointInRange(-10.0f, 10.0f);
    }
}

hdhair::Primvar anyPrimvar(FuzzedDataProvider& fuzz, const std::string& name, int tupleSize) {
    hdhair::Primvar primvar;
    primvar.name = name;
    primvar.tupleSize = fuzz.ConsumeBool() ? tupleSize : fuzz.ConsumeIntegralInRange(0, 4);
    primvar.interpolation = static_cast<hdhair::Interpolation>(fuzz.ConsumeIntegralInRange(0, 4));
    primvar.interpolationAuthored = fuzz.ConsumeBool();
    primvar.elementSize = fuzz.ConsumeIntegralInRange(-1, 3);
    const size_t values = fuzz.ConsumeIntegralInRange<size_t>(0, 64);
    for (size_t i = 0; i < values; ++i) primvar.values.push_back(anyFloat(fuzz));
    if (fuzz.ConsumeBool()) {
        const size_t indices = fuzz.ConsumeIntegralInRange<size_t>(0, 64);
        for (size_t i = 0; i < indices; ++i) primvar.indices.push_back(fuzz.ConsumeIntegralInRange(-2, 70));
    }
    return primvar;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider fuzz(data, size);
    hdhair::CurvesPrim prim;
    prim.path = "/fuzz";
    prim.type = fuzz.ConsumeBool() ? hdhair::CurveType::Linear : hdhair::CurveType::Cubic;
    prim.basis = static_cast<hdhair::CurveBasis>(fuzz.ConsumeIntegralInRange(0, 2));
    prim.wrap = static_cast<hdhair::CurveWrap>(fuzz.ConsumeIntegralInRange(0, 2));
    const size_t curves = fuzz.ConsumeIntegralInRange<size_t>(0, 16);
    for (size_t i = 0; i < curves; ++i)
        prim.curveVertexCounts.push_back(fuzz.ConsumeBool() ? fuzz.ConsumeIntegralInRange(-3, 12)
                                                            : fuzz.ConsumeIntegral<int>());
    const size_t points = fuzz.ConsumeIntegralInRange<size_t>(0, 96);
    for (size_t i = 0; i < points; ++i) prim.points.push_back({anyFloat(fuzz), anyFloat(fuzz), anyFloat(fuzz)});
    for (const char* name : {"widths", "displayColor", "displayOpacity", "hdHair:melanin"})
        if (fuzz.ConsumeBool()) prim.primvars[name] = anyPrimvar(fuzz, name, std::string(name) == "displayColor" ? 3 : 1);
    const size_t invisible = fuzz.ConsumeIntegralInRange<size_t>(0, 4);
    for (size_t i = 0; i < invisible; ++i) prim.invisibleCurves.push_back(fuzz.ConsumeIntegralInRange(-1, 20));
    prim.worldTransform[3][0] = anyFloat(fuzz);
    hdhair::Diagnostics diagnostics;
    hdhair::prepareCurves(prim, diagnostics, {{"hdHair:melanin", {0.3f}, 0.0f, 1.0f}});
    return 0;
}
