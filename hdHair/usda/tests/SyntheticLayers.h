#pragma once
// Generated .usda text for the reader's scaling tests and hdhair-bench's
// ParseLayer and ComposeStage rows: the tests check what is read and count
// the work, the benchmark times the same input.

#include <cstdio>
#include <random>
#include <string>

namespace hdhair::usda {

struct SyntheticCurvesLayer {
    std::string text;
    int curvesPrims = 0;  // "/World/hair0" ... each with 1,000 curves of 8 points
};

// BasisCurves prims of 1,000 eight-point curves with random points and
// vertex widths, until the text is at least `bytes` long.
inline SyntheticCurvesLayer syntheticCurvesLayer(size_t bytes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> dist(-10.0, 10.0);
    SyntheticCurvesLayer layer;
    std::string& text = layer.text;
    text = "#usda 1.0\n(\n    defaultPrim = \"World\"\n)\n\ndef Xform \"World\"\n{\n";
    char number[64];
    while (text.size() < bytes) {
        text += "    def BasisCurves \"hair" + std::to_string(layer.curvesPrims++) + "\"\n    {\n";
        text += "        int[] curveVertexCounts = [";
        for (int i = 0; i < 1000; ++i) text += i ? ", 8" : "8";
        text += "]\n        point3f[] points = [";
        for (int i = 0; i < 8000; ++i) {
            text += i ? ", (" : "(";
            for (int c = 0; c < 3; ++c) {
                std::snprintf(number, sizeof number, c ? ", %.7g" : "%.7g", dist(rng));
                text += number;
            }
            text += ")";
        }
        text += "]\n        float[] widths = [";
        for (int i = 0; i < 8000; ++i) {
            std::snprintf(number, sizeof number, i ? ", %.6g" : "%.6g", 0.01 + dist(rng) * 1e-4);
            text += number;
        }
        text += "] (\n            interpolation = \"vertex\"\n        )\n    }\n";
    }
    text += "}\n";
    return layer;
}

// `count` small BasisCurves prims "/World/c0" ... under one Xform, each with
// metadata and a relationship: composition cost per prim.
inline std::string siblingPrimsLayer(int count) {
    std::string text = "#usda 1.0\ndef Xform \"World\"\n{\n";
    for (int i = 0; i < count; ++i) {
        text += "    def BasisCurves \"c" + std::to_string(i) + "\" (\n        kind = \"subcomponent\"\n    )\n    {\n"
                "        int[] curveVertexCounts = [4]\n        point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), "
                "(0, 3, 0)]\n        rel material:binding = </World/m>\n    }\n";
    }
    return text + "}\n";
}

}  // namespace hdhair::usda
