#pragma once
// Stages with bad lights, transforms and materials (docs/hard-cases.md, rows
// 1-17 and 37-39): each is repaired or skipped with a warning naming the prim
// and attribute. testHardCases renders them in process and checks every
// AOV; testReaderVerdicts runs them through hdhair-record with both readers.

#include <string>

namespace hdhair::testenv {

// Three lit strands across an orthographic camera /cam 12 units wide; `hair`
// goes inside the BasisCurves prim, `extra` after it (lights, materials).
inline std::string stageText(const std::string& hair, const std::string& extra) {
    return R"(#usda 1.0
(
    upAxis = "Y"
)
def Camera "cam" {
    token projection = "orthographic"
    float horizontalAperture = 120
    float verticalAperture = 120
    float2 clippingRange = (0.1, 100)
    double3 xformOp:translate = (0, 0, 10)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def BasisCurves "hair" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2, 2, 2]
    point3f[] points = [(-5, -2, 0), (5, -2, 0), (-5, 0, 0), (5, 0, 0), (-5, 2, 0), (5, 2, 0)]
    float[] primvars:widths = [0.5] (interpolation = "constant")
    color3f[] primvars:displayColor = [(0.8, 0.5, 0.3)] (interpolation = "constant")
)" + hair + "\n}\n" +
           extra + "\n";
}

struct InputCase {
    const char* name;
    std::string hair;     // inside the curves prim
    std::string extra;    // after it
    std::string warning;  // a warning containing this must appear
    bool drawn;           // the strands still cover pixels
};

inline const std::string kDistant = "def DistantLight \"sun\" {\n";
inline const std::string kSphere =
    "def SphereLight \"bulb\" {\n double3 xformOp:translate = (0, 0, 5)\n uniform token[] xformOpOrder = "
    "[\"xformOp:translate\"]\n";

// The cases of HardCases.BadInputsWarnNameThePrimAndAttributeAndLeaveEveryAovFinite.
inline const InputCase kBadInputs[] = {
        InputCase{"nanIntensity", "", kDistant + " float inputs:intensity = nan\n}", "/sun.inputs:intensity: nan is not a number", true},
        InputCase{"infIntensity", "", kDistant + " float inputs:intensity = inf\n}", "/sun.inputs:intensity: inf is not a number", true},
        InputCase{"negativeIntensity", "", kDistant + " float inputs:intensity = -3\n}", "/sun.inputs:intensity: -3 is negative", true},
        InputCase{"nanExposure", "", kDistant + " float inputs:exposure = nan\n}", "/sun.inputs:exposure: nan is not a number", true},
        InputCase{"hugeExposure", "", kDistant + " float inputs:exposure = 1000\n}", "beyond float range; light skipped", true},
        InputCase{"nanColor", "", kDistant + " color3f inputs:color = (nan, 1, 1)\n}", "/sun.inputs:color: (nan, 1, 1)", true},
        InputCase{"negativeColor", "", kDistant + " color3f inputs:color = (-1, 1, 1)\n}", "/sun.inputs:color: (-1, 1, 1) has a negative component", true},
        InputCase{"nanColorTemperature", "", kDistant + " bool inputs:enableColorTemperature = 1\n float inputs:colorTemperature = nan\n}", "/sun.inputs:colorTemperature: nan", true},
        InputCase{"zeroColorTemperature", "", kDistant + " bool inputs:enableColorTemperature = 1\n float inputs:colorTemperature = 0\n}", "/sun.inputs:colorTemperature: 0 K is not a temperature", true},
        InputCase{"nanRadius", "", kSphere + " float inputs:radius = nan\n}", "/bulb.inputs:radius: nan", true},
        InputCase{"negativeRadius", "", kSphere + " float inputs:radius = -1\n}", "/bulb.inputs:radius: -1 is negative", true},
        InputCase{"infRectWidth", "", "def RectLight \"panel\" {\n double3 xformOp:translate = (0, 0, 5)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]\n float inputs:width = inf\n float inputs:height = -2\n}", "/panel.inputs:width: inf", true},
        InputCase{"hugeRectArea", "", "def RectLight \"panel\" {\n double3 xformOp:translate = (0, 0, 5)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]\n float inputs:width = 1e30\n float inputs:height = 1e30\n}", "beyond float range; light skipped", true},
        InputCase{"nanCone", "", kSphere + " float inputs:shaping:cone:angle = nan\n float inputs:shaping:cone:softness = 7\n}", "/bulb.inputs:shaping:cone:softness: 7 is outside [0, 1]", true},
        InputCase{"nanLightTransform", "", "def DistantLight \"sun\" {\n double3 xformOp:rotateXYZ = (nan, 0, 0)\n uniform token[] xformOpOrder = [\"xformOp:rotateXYZ\"]\n}", "/sun: the world transform is not finite", true},
        InputCase{"zeroScaleLight", "", "def DistantLight \"sun\" {\n float3 xformOp:scale = (1, 1, 0)\n uniform token[] xformOpOrder = [\"xformOp:scale\"]\n}", "/sun: the world transform scales the light's -Z axis to nothing", true},
        InputCase{"nanDome", "", "def DomeLight \"sky\" {\n float inputs:intensity = nan\n color3f inputs:color = (inf, 0, 0)\n}", "/sky.inputs:intensity: nan", true},
        InputCase{"nanPrimTransform", " double3 xformOp:translate = (nan, 0, 0)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]", "", "/hair: the world transform is not finite", false},
        InputCase{"singularInvert", " float3 xformOp:scale = (0, 1, 1)\n uniform token[] xformOpOrder = [\"!invert!xformOp:scale\"]", "", "/hair: the world transform is not finite", false},
        InputCase{"nanMaterialColor", " rel material:binding = </Looks/bad>",
                  "def Scope \"Looks\" {\n def Material \"bad\" {\n  token outputs:surface.connect = </Looks/bad/surface.outputs:surface>\n  def Shader \"surface\" {\n   uniform token info:id = \"UsdPreviewSurface\"\n   color3f inputs:diffuseColor = (nan, 0.5, 0.5)\n   float inputs:opacity = inf\n   token outputs:surface\n  }\n }\n}",
                  "/Looks/bad.inputs:diffuseColor: (nan, 0.5, 0.5) is not finite; using UsdPreviewSurface's default", true}};

}  // namespace hdhair::testenv
