#pragma once
// Every example and testenv stage, in one list: the baseline test renders
// each one that has a baseline image, the reader-parity test renders every
// one through OpenUSD and the embedded reader, and a test checks that no
// stage file is missing here. Add a new stage to this list only.

#include <ostream>
#include <string>
#include <vector>

namespace hdhair::testenv {

struct TestStage {
    const char* name;    // names its baseline image and test outputs
    const char* path;    // from the source root
    const char* camera;
    // Baseline images: the width, and the time codes (one image each; a
    // stage with several gets "<name>_time<t>" images). 0: no baseline, a
    // dedicated test checks the stage instead.
    int baselineWidth;
    std::vector<double> baselineTimes;
};

// GoogleTest prints a parameter in test listings: by name, not as bytes.
inline void PrintTo(const TestStage& stage, std::ostream* os) { *os << stage.name; }

inline const std::vector<TestStage>& testStages() {
    static const std::vector<TestStage> stages = {
        {"straight_strands", "examples/straight_strands.usda", "/World/main_cam", 320, {0.0}},
        {"wavy_strands", "examples/wavy_strands.usda", "/World/main_cam", 320, {0.0}},
        {"dense_clump", "examples/dense_clump.usda", "/World/main_cam", 320, {0.0}},
        // No baseline yet: the dome's SRBF lighting is checked pixel by pixel in testDomeLighting.
        {"dome_lit_strands", "examples/dome_lit_strands.usda", "/World/main_cam", 0, {}},
        {"bases", "testenv/stages/bases.usda", "/World/main_cam", 320, {0.0}},
        {"interpolations", "testenv/stages/interpolations.usda", "/World/main_cam", 256, {0.0}},
        {"hair_parameters", "testenv/stages/hair_parameters.usda", "/World/main_cam", 256, {0.0}},
        {"xforms", "testenv/stages/xforms.usda", "/World/main_cam", 256, {1.0, 10.0}},
        {"widths", "testenv/stages/widths.usda", "/World/main_cam", 0, {}},
        {"widths_doubled", "testenv/stages/widths_doubled.usda", "/World/main_cam", 0, {}},
        {"empty", "testenv/stages/empty.usda", "/World/main_cam", 0, {}},
        {"composition", "testenv/stages/composition/root.usda", "/World/main_cam", 256, {0.0}},
        {"materials", "testenv/stages/materials.usda", "/World/main_cam", 256, {0.0}},
        {"instancing", "testenv/stages/instancing/root.usda", "/World/main_cam", 256, {0.0}},
        {"meshes", "testenv/stages/meshes.usda", "/World/main_cam", 256, {0.0}},
    };
    return stages;
}

}  // namespace hdhair::testenv
