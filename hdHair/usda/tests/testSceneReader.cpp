#include <limits>

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "hdHair/base/InputError.h"
#include "hdHair/usda/SceneReader.h"

using namespace hdhair;
using namespace hdhair::usda;

namespace {

struct Read {
    std::unique_ptr<Stage> stage;
    Scene scene;
    Diagnostics diagnostics;
};

// `text` is the whole layer after "#usda 1.0".
std::unique_ptr<Read> read(const std::string& text, double time = 0.0,
                           const SceneReadOptions& options = {}) {
    auto result = std::make_unique<Read>();
    result->stage = Stage::openFromString("#usda 1.0\n" + text, "scene.usda");
    readScene(*result->stage, time, result->scene, result->diagnostics, options);
    return result;
}

// The first warning whose "where: message" contains every fragment.
bool hasWarning(const Diagnostics& diagnostics, std::initializer_list<const char*> fragments) {
    for (const Diagnostic& d : diagnostics.warnings()) {
        std::string text = d.where + ": " + d.message;
        bool all = true;
        for (const char* fragment : fragments) all = all && text.find(fragment) != std::string::npos;
        if (all) return true;
    }
    return false;
}

std::string allWarnings(const Diagnostics& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics.warnings()) text += d.where + ": " + d.message + "\n";
    return text;
}

glm::dvec3 apply(const glm::dmat4& m, glm::dvec3 p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

void expectNear(glm::dvec3 actual, glm::dvec3 expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-6);
    EXPECT_NEAR(actual.y, expected.y, 1e-6);
    EXPECT_NEAR(actual.z, expected.z, 1e-6);
}

const char* const kOneCurve = R"(
        int[] curveVertexCounts = [4]
        point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0)]
)";

}  // namespace

TEST(SceneReader, HierarchyTransformsCompose) {
    auto r = read(std::string(R"(
def Xform "World"
{
    double3 xformOp:translate = (1, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def Scope "Group"
    {
        def Xform "Scaled"
        {
            float3 xformOp:scale = (2, 2, 2)
            uniform token[] xformOpOrder = ["xformOp:scale"]

            def BasisCurves "hair"
            {
                double3 xformOp:translate = (0, 1, 0)
                uniform token[] xformOpOrder = ["xformOp:translate"]
)") + kOneCurve + R"(
            }
        }
    }
}
)");
    const CurvesPrim* hair = r->scene.findCurves("/World/Group/Scaled/hair");
    ASSERT_NE(hair, nullptr) << allWarnings(r->diagnostics);
    // Local first: (0,0,0) -> (0,1,0) -> scale 2 -> (0,2,0) -> (1,2,0).
    expectNear(apply(hair->worldTransform, {0, 0, 0}), {1, 2, 0});
    expectNear(apply(hair->worldTransform, {1, 0, 0}), {3, 2, 0});
    EXPECT_EQ(r->diagnostics.warningCount(), 0u) << allWarnings(r->diagnostics);
}

TEST(SceneReader, ResetXformStackIgnoresParents) {
    auto r = read(std::string(R"(
def Xform "World"
{
    double3 xformOp:translate = (5, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def BasisCurves "hair"
    {
        double3 xformOp:translate = (0, 1, 0)
        uniform token[] xformOpOrder = ["!resetXformStack!", "xformOp:translate"]
)") + kOneCurve + R"(
        def Xform "child"
        {
            def Camera "cam"
            {
            }
        }
    }
}
)");
    const CurvesPrim* hair = r->scene.findCurves("/World/hair");
    ASSERT_NE(hair, nullptr);
    expectNear(apply(hair->worldTransform, {0, 0, 0}), {0, 1, 0});
    // Descendants build on the reset transform.
    const CameraPrim* cam = r->scene.findCamera("/World/hair/child/cam");
    ASSERT_NE(cam, nullptr);
    expectNear(apply(cam->worldTransform, {0, 0, 0}), {0, 1, 0});
}

TEST(SceneReader, MissingXformOpIsAnInputError) {
    EXPECT_THROW(read(R"(
def Xform "World"
{
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
)"),
                 InputError);
}

TEST(SceneReader, InvisibleHidesTheSubtree) {
    auto r = read(std::string(R"(
def Xform "World"
{
    def Xform "Hidden"
    {
        token visibility = "invisible"
        def BasisCurves "a"
        {
            token visibility = "inherited"
)") + kOneCurve + R"(
        }
        def DistantLight "sun"
        {
        }
    }
    def BasisCurves "b"
    {
)" + kOneCurve + R"(
    }
    def BasisCurves "c"
    {
        token visibility.timeSamples = { 0: "inherited", 10: "invisible" }
)" + kOneCurve + R"(
    }
}
)");
    ASSERT_NE(r->scene.findCurves("/World/Hidden/a"), nullptr);
    EXPECT_FALSE(r->scene.findCurves("/World/Hidden/a")->visible);
    EXPECT_TRUE(r->scene.findCurves("/World/b")->visible);
    EXPECT_TRUE(r->scene.findCurves("/World/c")->visible);
    ASSERT_EQ(r->scene.lights().count("/World/Hidden/sun"), 1u);
    EXPECT_FALSE(r->scene.lights().at("/World/Hidden/sun").prim->visible);

    auto later = read(std::string(R"(
def BasisCurves "c"
{
    token visibility.timeSamples = { 0: "inherited", 10: "invisible" }
)") + kOneCurve + "}\n",
                      10.0);
    EXPECT_FALSE(later->scene.findCurves("/c")->visible);
}

TEST(SceneReader, PurposeKeepsDefaultAndRenderGeometry) {
    const std::string text = std::string(R"(
def Xform "World"
{
    def BasisCurves "plain"
    {
)") + kOneCurve + R"(
    }
    def BasisCurves "final"
    {
        uniform token purpose = "render"
)" + kOneCurve + R"(
    }
    def BasisCurves "stand_in"
    {
        uniform token purpose = "proxy"
)" + kOneCurve + R"(
    }
    def Xform "Guides"
    {
        uniform token purpose = "guide"
        def BasisCurves "guide"
        {
            uniform token purpose = "render"
)" + kOneCurve + R"(
        }
        def SphereLight "light"
        {
        }
    }
}
)";
    auto r = read(text);
    EXPECT_NE(r->scene.findCurves("/World/plain"), nullptr);
    EXPECT_NE(r->scene.findCurves("/World/final"), nullptr);
    EXPECT_EQ(r->scene.findCurves("/World/stand_in"), nullptr);
    // The highest authored purpose wins: the child's "render" is ignored.
    EXPECT_EQ(r->scene.findCurves("/World/Guides/guide"), nullptr);
    // Purpose does not apply to lights.
    EXPECT_EQ(r->scene.lights().count("/World/Guides/light"), 1u);

    SceneReadOptions options;
    options.renderPurpose = false;
    options.proxyPurpose = true;
    auto proxies = read(text, 0.0, options);
    EXPECT_NE(proxies->scene.findCurves("/World/plain"), nullptr);
    EXPECT_EQ(proxies->scene.findCurves("/World/final"), nullptr);
    EXPECT_NE(proxies->scene.findCurves("/World/stand_in"), nullptr);
}

TEST(SceneReader, InactiveAndClassPrimsAreSkipped) {
    // An active sibling is read: the others are left out, not lost with a
    // stage that failed to read.
    auto r = read(std::string(R"(
def Xform "World"
{
    def Xform "Off" (
        active = false
    )
    {
        def BasisCurves "hair"
        {
)") + kOneCurve + R"(
        }
    }
    def BasisCurves "on"
    {
)" + kOneCurve + R"(
    }
}
class BasisCurves "Template"
{
)" + kOneCurve + R"(
}
)");
    ASSERT_EQ(r->scene.curves().size(), 1u);
    EXPECT_NE(r->scene.findCurves("/World/on"), nullptr);
}

TEST(SceneReader, EveryLightType) {
    auto r = read(R"(
def DistantLight "distant"
{
    float inputs:intensity = 3
    float inputs:exposure = 1.5
    color3f inputs:color = (1, 0.5, 0.25)
    float inputs:angle = 2
    bool inputs:normalize = true
    bool inputs:shadow:enable = false
}
def SphereLight "sphere"
{
    float inputs:radius = 0.25
    bool inputs:enableColorTemperature = true
    float inputs:colorTemperature = 3200
    float inputs:shaping:cone:angle = 30
    float inputs:shaping:cone:softness = 0.2
}
def RectLight "rect"
{
    float inputs:width = 2
    float inputs:height = 3
    double3 xformOp:translate = (0, 4, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def DiskLight "disk"
{
    float inputs:radius = 1.5
}
def DomeLight "dome"
{
    float inputs:intensity = 0.5
}
def SphereLight "old"
{
    float intensity = 7
    color3f color = (0, 1, 0)
    float radius = 2
    float shaping:cone:angle = 45
    float shaping:cone:softness = 0.5
    bool shadow:enable = 0
}
def SphereLight "both"
{
    float inputs:intensity = 4
    float intensity = 9
}
)");
    EXPECT_EQ(r->diagnostics.warningCount(), 0u) << allWarnings(r->diagnostics);
    auto light = [&](const char* path) -> const LightPrim& {
        return *r->scene.lights().at(path).prim;
    };
    ASSERT_EQ(r->scene.lights().size(), 7u);

    const LightPrim& distant = light("/distant");
    EXPECT_EQ(distant.type, LightType::Distant);
    EXPECT_FLOAT_EQ(distant.intensity, 3.0f);
    EXPECT_FLOAT_EQ(distant.exposure, 1.5f);
    EXPECT_EQ(distant.color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(distant.angle, 2.0f);
    EXPECT_TRUE(distant.normalize);
    EXPECT_TRUE(distant.visible);
    EXPECT_FALSE(distant.shadowEnable);

    const LightPrim& sphere = light("/sphere");
    EXPECT_EQ(sphere.type, LightType::Sphere);
    EXPECT_FLOAT_EQ(sphere.intensity, 1.0f);  // schema fallback
    EXPECT_FLOAT_EQ(sphere.radius, 0.25f);
    EXPECT_TRUE(sphere.enableColorTemperature);
    EXPECT_FLOAT_EQ(sphere.colorTemperature, 3200.0f);
    EXPECT_FLOAT_EQ(sphere.coneAngle, 30.0f);
    EXPECT_FLOAT_EQ(sphere.coneSoftness, 0.2f);
    EXPECT_TRUE(sphere.shadowEnable);  // ShadowAPI's fallback

    const LightPrim& rect = light("/rect");
    EXPECT_EQ(rect.type, LightType::Rect);
    EXPECT_FLOAT_EQ(rect.width, 2.0f);
    EXPECT_FLOAT_EQ(rect.height, 3.0f);
    expectNear(apply(rect.worldTransform, {0, 0, 0}), {0, 4, 0});

    EXPECT_EQ(light("/disk").type, LightType::Disk);
    EXPECT_FLOAT_EQ(light("/disk").radius, 1.5f);
    EXPECT_EQ(light("/dome").type, LightType::Dome);
    EXPECT_FLOAT_EQ(light("/dome").intensity, 0.5f);
    EXPECT_FLOAT_EQ(light("/dome").coneAngle, 90.0f);

    // Pre-21.02 names without "inputs:".
    const LightPrim& old = light("/old");
    EXPECT_FLOAT_EQ(old.intensity, 7.0f);
    EXPECT_EQ(old.color, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(old.radius, 2.0f);
    EXPECT_FLOAT_EQ(old.coneAngle, 45.0f);
    EXPECT_FLOAT_EQ(old.coneSoftness, 0.5f);
    EXPECT_FALSE(old.shadowEnable);
    // The "inputs:" name wins when both are authored.
    EXPECT_FLOAT_EQ(light("/both").intensity, 4.0f);
}

TEST(SceneReader, DomeTextureFileAndFormat) {
    auto r = read(R"(
def DomeLight "sky"
{
    asset inputs:texture:file = @textures/../sky.exr@
    token inputs:texture:format = "latlong"
}
def DomeLight "old"
{
    asset texture:file = @/maps/sky.hdr@
    token texture:format = "angular"
}
def DomeLight "plain"
{
}
def DomeLight "wrongType"
{
    string inputs:texture:file = "sky.exr"
}
def SphereLight "notADome"
{
    asset inputs:texture:file = @sky.exr@
}
)");
    auto light = [&](const char* path) -> const LightPrim& { return *r->scene.lights().at(path).prim; };
    // openFromString's layer lives in the current directory.
    const std::string here = std::filesystem::current_path().lexically_normal().string();
    EXPECT_EQ(light("/sky").textureFile, here + "/sky.exr");
    EXPECT_EQ(light("/sky").textureFormat, "latlong");
    EXPECT_EQ(light("/old").textureFile, "/maps/sky.hdr");
    EXPECT_EQ(light("/old").textureFormat, "angular");  // kept as authored: hdHair/environment checks it
    EXPECT_EQ(light("/plain").textureFile, "");
    EXPECT_EQ(light("/plain").textureFormat, "automatic");
    EXPECT_EQ(light("/notADome").textureFile, "");
    // A texture of the wrong type leaves the dome untextured, with a word.
    EXPECT_EQ(light("/wrongType").textureFile, "");
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/wrongType.inputs:texture:file", "expected an asset path", "string"}))
        << allWarnings(r->diagnostics);
    EXPECT_EQ(r->diagnostics.warningCount(), 1u) << allWarnings(r->diagnostics);
}

TEST(SceneReader, CameraFields) {
    auto r = read(R"(
def Camera "persp"
{
    float focalLength = 35
    float horizontalAperture = 36
    float verticalAperture = 24
    float horizontalApertureOffset = 1.5
    float verticalApertureOffset = -0.5
    float2 clippingRange = (0.1, 500)
    double3 xformOp:translate = (0, 0, 10)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def Camera "ortho"
{
    token projection = "orthographic"
}
def Camera "fisheye"
{
    token projection = "fisheye"
}
)");
    const CameraPrim* persp = r->scene.findCamera("/persp");
    ASSERT_NE(persp, nullptr);
    EXPECT_EQ(persp->projection, Projection::Perspective);
    EXPECT_FLOAT_EQ(persp->focalLength, 35.0f);
    EXPECT_FLOAT_EQ(persp->horizontalAperture, 36.0f);
    EXPECT_FLOAT_EQ(persp->verticalAperture, 24.0f);
    EXPECT_FLOAT_EQ(persp->horizontalApertureOffset, 1.5f);
    EXPECT_FLOAT_EQ(persp->verticalApertureOffset, -0.5f);
    EXPECT_FLOAT_EQ(persp->clippingRange.x, 0.1f);
    EXPECT_FLOAT_EQ(persp->clippingRange.y, 500.0f);
    expectNear(apply(persp->worldTransform, {0, 0, 0}), {0, 0, 10});

    const CameraPrim* ortho = r->scene.findCamera("/ortho");
    ASSERT_NE(ortho, nullptr);
    EXPECT_EQ(ortho->projection, Projection::Orthographic);
    // UsdGeomCamera fallbacks.
    EXPECT_FLOAT_EQ(ortho->focalLength, 50.0f);
    EXPECT_FLOAT_EQ(ortho->horizontalAperture, 20.955f);
    EXPECT_FLOAT_EQ(ortho->verticalAperture, 15.2908f);
    EXPECT_FLOAT_EQ(ortho->clippingRange.x, 1.0f);
    EXPECT_FLOAT_EQ(ortho->clippingRange.y, 1000000.0f);

    ASSERT_NE(r->scene.findCamera("/fisheye"), nullptr);
    EXPECT_EQ(r->scene.findCamera("/fisheye")->projection, Projection::Perspective);
    EXPECT_TRUE(hasWarning(r->diagnostics, {"scene.usda:", "/fisheye.projection", "fisheye"}))
        << allWarnings(r->diagnostics);
}

TEST(SceneReader, CurveTopologyTokensAndPoints) {
    auto r = read(std::string(R"(
def BasisCurves "hair"
{
    uniform token type = "cubic"
    uniform token basis = "catmullRom"
    uniform token wrap = "pinned"
)") + kOneCurve + R"(
}
def BasisCurves "defaults"
{
)" + kOneCurve + R"(
}
def BasisCurves "odd"
{
    uniform token type = "quadratic"
    uniform token basis = "hermite"
    uniform token wrap = "sometimes"
)" + kOneCurve + R"(
}
)");
    const CurvesPrim* hair = r->scene.findCurves("/hair");
    ASSERT_NE(hair, nullptr);
    EXPECT_EQ(hair->type, CurveType::Cubic);
    EXPECT_EQ(hair->basis, CurveBasis::CatmullRom);
    EXPECT_EQ(hair->wrap, CurveWrap::Pinned);
    EXPECT_EQ(hair->curveVertexCounts, std::vector<int>{4});
    ASSERT_EQ(hair->points.size(), 4u);
    EXPECT_EQ(hair->points[3], glm::vec3(0, 3, 0));
    EXPECT_EQ(hair->sourceFile, r->stage->rootLayerPath());
    EXPECT_EQ(hair->path, "/hair");

    const CurvesPrim* defaults = r->scene.findCurves("/defaults");
    EXPECT_EQ(defaults->type, CurveType::Cubic);
    EXPECT_EQ(defaults->basis, CurveBasis::Bezier);
    EXPECT_EQ(defaults->wrap, CurveWrap::Nonperiodic);

    const CurvesPrim* odd = r->scene.findCurves("/odd");
    ASSERT_NE(odd, nullptr);
    EXPECT_EQ(odd->type, CurveType::Cubic);
    EXPECT_EQ(odd->basis, CurveBasis::Bezier);
    EXPECT_EQ(odd->wrap, CurveWrap::Nonperiodic);
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/odd.type", "quadratic"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/odd.basis", "hermite"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/odd.wrap", "sometimes"}));
}

TEST(SceneReader, WidthsAttributeAndPrimvarPrecedence) {
    auto r = read(std::string(R"(
def BasisCurves "attribute"
{
)") + kOneCurve + R"(
    float[] widths = [0.1, 0.2, 0.3, 0.4]
}
def BasisCurves "attributeConstant"
{
)" + kOneCurve + R"(
    float[] widths = [0.5] (
        interpolation = "constant"
    )
}
def BasisCurves "both"
{
)" + kOneCurve + R"(
    float[] widths = [0.1, 0.2, 0.3, 0.4]
    float[] primvars:widths = [0.7]
}
def BasisCurves "primvarVarying"
{
)" + kOneCurve + R"(
    float[] primvars:widths = [1, 2] (
        interpolation = "varying"
    )
}
def BasisCurves "blockedPrimvar"
{
)" + kOneCurve + R"(
    float[] widths = [0.25] (
        interpolation = "constant"
    )
    float[] primvars:widths = None
}
)");
    EXPECT_EQ(r->diagnostics.warningCount(), 0u) << allWarnings(r->diagnostics);

    const Primvar* widths = r->scene.findCurves("/attribute")->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->values, (std::vector<float>{0.1f, 0.2f, 0.3f, 0.4f}));
    EXPECT_EQ(widths->interpolation, Interpolation::Vertex);  // the widths attribute's default
    EXPECT_FALSE(widths->interpolationAuthored);
    EXPECT_EQ(widths->tupleSize, 1);
    EXPECT_EQ(widths->typeName, "float[]");

    widths = r->scene.findCurves("/attributeConstant")->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->interpolation, Interpolation::Constant);
    EXPECT_TRUE(widths->interpolationAuthored);

    widths = r->scene.findCurves("/both")->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->values, std::vector<float>{0.7f});
    EXPECT_EQ(widths->interpolation, Interpolation::Constant);  // a primvar's default
    EXPECT_FALSE(widths->interpolationAuthored);

    widths = r->scene.findCurves("/primvarVarying")->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->interpolation, Interpolation::Varying);
    EXPECT_TRUE(widths->interpolationAuthored);

    // A blocked primvar has no value: the attribute is used.
    widths = r->scene.findCurves("/blockedPrimvar")->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->values, std::vector<float>{0.25f});

    // Nothing authored: nothing stored (hdHair/curves applies the fallback).
    auto bare = read(std::string("def BasisCurves \"bare\"\n{\n") + kOneCurve + "}\n");
    EXPECT_EQ(bare->scene.findCurves("/bare")->findPrimvar("widths"), nullptr);
}

TEST(SceneReader, NormalsAttributeAndPrimvar) {
    auto r = read(std::string(R"(
def BasisCurves "attribute"
{
)") + kOneCurve + R"(
    normal3f[] normals = [(0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1)]
}
def BasisCurves "primvar"
{
)" + kOneCurve + R"(
    normal3f[] normals = [(0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1)]
    normal3f[] primvars:normals = [(1, 0, 0)] (
        interpolation = "constant"
    )
}
)");
    const Primvar* normals = r->scene.findCurves("/attribute")->findPrimvar("normals");
    ASSERT_NE(normals, nullptr);
    EXPECT_EQ(normals->tupleSize, 3);
    EXPECT_EQ(normals->elementCount(), 4u);
    EXPECT_EQ(normals->interpolation, Interpolation::Vertex);
    normals = r->scene.findCurves("/primvar")->findPrimvar("normals");
    ASSERT_NE(normals, nullptr);
    EXPECT_EQ(normals->values, (std::vector<float>{1, 0, 0}));
    EXPECT_EQ(normals->interpolation, Interpolation::Constant);
}

TEST(SceneReader, IndexedPrimvarsAndMetadata) {
    auto r = read(R"(
def BasisCurves "hair"
{
    int[] curveVertexCounts = [4, 4]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0), (1, 0, 0), (1, 1, 0), (1, 2, 0), (1, 3, 0)]
    color3f[] primvars:displayColor = [(1, 0, 0), (0, 0, 1)] (
        interpolation = "uniform"
    )
    int[] primvars:displayColor:indices = [1, 0]
    float[] primvars:displayOpacity = [0.5]
    float[] primvars:hair:melanin = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6] (
        interpolation = "uniform"
        elementSize = 3
    )
    float2[] primvars:st = [(0, 0), (1, 1)] (
        interpolation = "sideways"
    )
    token[] primvars:groom:style = ["curly", "straight"]
    string primvars:note = "for the material"
    int[] primvars:id = [7, 8] (
        interpolation = "uniform"
    )
    bool primvars:flag = true
}
)");
    const CurvesPrim* hair = r->scene.findCurves("/hair");
    ASSERT_NE(hair, nullptr);

    const Primvar* color = hair->findPrimvar("displayColor");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->name, "displayColor");
    EXPECT_EQ(color->typeName, "color3f[]");
    EXPECT_EQ(color->tupleSize, 3);
    EXPECT_EQ(color->values, (std::vector<float>{1, 0, 0, 0, 0, 1}));
    EXPECT_EQ(color->indices, (std::vector<int>{1, 0}));
    EXPECT_EQ(color->interpolation, Interpolation::Uniform);
    EXPECT_TRUE(color->interpolationAuthored);
    EXPECT_EQ(color->authoredCount(), 2u);

    const Primvar* opacity = hair->findPrimvar("displayOpacity");
    ASSERT_NE(opacity, nullptr);
    EXPECT_EQ(opacity->interpolation, Interpolation::Constant);  // primvar default
    EXPECT_FALSE(opacity->interpolationAuthored);
    EXPECT_TRUE(opacity->indices.empty());

    const Primvar* melanin = hair->findPrimvar("hair:melanin");
    ASSERT_NE(melanin, nullptr);
    EXPECT_EQ(melanin->elementSize, 3);
    EXPECT_EQ(melanin->elementCount(), 6u);

    // An unknown interpolation is reported and the primvar default used.
    const Primvar* st = hair->findPrimvar("st");
    ASSERT_NE(st, nullptr);
    EXPECT_EQ(st->tupleSize, 2);
    EXPECT_EQ(st->interpolation, Interpolation::Constant);
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/hair.primvars:st", "sideways"}))
        << allWarnings(r->diagnostics);

    // Integers and bools are numeric; tokens and strings are skipped.
    ASSERT_NE(hair->findPrimvar("id"), nullptr);
    EXPECT_EQ(hair->findPrimvar("id")->values, (std::vector<float>{7, 8}));
    ASSERT_NE(hair->findPrimvar("flag"), nullptr);
    EXPECT_EQ(hair->findPrimvar("flag")->values, std::vector<float>{1});
    EXPECT_EQ(hair->findPrimvar("groom:style"), nullptr);
    EXPECT_EQ(hair->findPrimvar("note"), nullptr);
    // The indices attribute is not a primvar of its own.
    EXPECT_EQ(hair->findPrimvar("displayColor:indices"), nullptr);
    EXPECT_EQ(hair->primvars.size(), 6u);
}

TEST(SceneReader, TimeSamplesAreReadAtTheTime) {
    const std::string text = R"(
def BasisCurves "hair"
{
    int[] curveVertexCounts = [2]
    uniform token type = "linear"
    point3f[] points.timeSamples = {
        0: [(0, 0, 0), (0, 1, 0)],
        10: [(0, 0, 0), (10, 1, 0)],
    }
    float[] primvars:widths.timeSamples = { 0: [1], 10: [3] }
    double3 xformOp:translate.timeSamples = { 0: (0, 0, 0), 10: (0, 0, 20) }
    uniform token[] xformOpOrder = ["xformOp:translate"]
}
def SphereLight "light"
{
    float inputs:intensity.timeSamples = { 0: 1, 10: 11 }
}
)";
    auto r = read(text, 5.0);
    const CurvesPrim* hair = r->scene.findCurves("/hair");
    ASSERT_NE(hair, nullptr) << allWarnings(r->diagnostics);
    ASSERT_EQ(hair->points.size(), 2u);
    EXPECT_FLOAT_EQ(hair->points[1].x, 5.0f);
    EXPECT_FLOAT_EQ(hair->findPrimvar("widths")->values[0], 2.0f);
    expectNear(apply(hair->worldTransform, {0, 0, 0}), {0, 0, 10});
    EXPECT_FLOAT_EQ(r->scene.lights().at("/light").prim->intensity, 6.0f);

    auto end = read(text, 10.0);
    EXPECT_FLOAT_EQ(end->scene.findCurves("/hair")->points[1].x, 10.0f);
}

TEST(SceneReader, DefaultAndEarliestTimeCodes) {
    // hdhair-record passes NaN for UsdTimeCode::Default() (--defaultTime) and
    // -infinity for UsdTimeCode::EarliestTime() (usdrecord's default).
    const std::string text = R"(
def SphereLight "light"
{
    float inputs:intensity = 3
    float inputs:intensity.timeSamples = { 2: 7, 10: 11 }
    float inputs:exposure.timeSamples = { 2: 1, 10: 2 }
}
)";
    auto atDefault = read(text, std::numeric_limits<double>::quiet_NaN());
    const LightPrim& light = *atDefault->scene.lights().at("/light").prim;
    EXPECT_FLOAT_EQ(light.intensity, 3.0f);  // the default value, samples ignored
    EXPECT_FLOAT_EQ(light.exposure, 0.0f);   // samples only: no value, the schema fallback
    auto earliest = read(text, -std::numeric_limits<double>::infinity());
    EXPECT_FLOAT_EQ(earliest->scene.lights().at("/light").prim->intensity, 7.0f);
    EXPECT_FLOAT_EQ(earliest->scene.lights().at("/light").prim->exposure, 1.0f);
}

TEST(SceneReader, BadTypesWarnAndSkipThePrim) {
    auto r = read(std::string(R"(
def Xform "World"
{
    def BasisCurves "floatPoints"
    {
        int[] curveVertexCounts = [2]
        float[] points = [0, 0, 0, 0, 1, 0]
    }
    def BasisCurves "floatCounts"
    {
        float[] curveVertexCounts = [4.5]
        point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0)]
    }
    def BasisCurves "vectorWidths"
    {
)") + kOneCurve + R"(
        float3[] widths = [(1, 1, 1)]
    }
    def BasisCurves "tokenType"
    {
)" + kOneCurve + R"(
        uniform int type = 3
    }
    def BasisCurves "floatIndices"
    {
)" + kOneCurve + R"(
        color3f[] primvars:displayColor = [(1, 0, 0)]
        float[] primvars:displayColor:indices = [0.5]
    }
    def SphereLight "tokenIntensity"
    {
        token inputs:intensity = "bright"
    }
    def Camera "arrayFocal"
    {
        float[] focalLength = [35, 50]
    }
    def BasisCurves "good"
    {
)" + kOneCurve + R"(
    }
}
)");
    EXPECT_EQ(r->scene.curves().size(), 1u);
    EXPECT_NE(r->scene.findCurves("/World/good"), nullptr);
    EXPECT_TRUE(r->scene.lights().empty());
    EXPECT_TRUE(r->scene.cameras().empty());
    // "file:line:col" of the attribute, then "/Prim.attr".
    EXPECT_TRUE(hasWarning(r->diagnostics, {"scene.usda:8:", "/World/floatPoints.points",
                                            "point3f[]", "float[]", "skipped"}))
        << allWarnings(r->diagnostics);
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/floatCounts.curveVertexCounts", "int[]"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/vectorWidths.widths", "float3[]"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/tokenType.type", "token"}));
    EXPECT_TRUE(
        hasWarning(r->diagnostics, {"/World/floatIndices.primvars:displayColor:indices", "int[]"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/tokenIntensity.inputs:intensity"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/arrayFocal.focalLength"}));
    EXPECT_EQ(r->diagnostics.warningCount(), 7u) << allWarnings(r->diagnostics);
}

// An integer beyond 32 bits says which element and why, not "expected int[],
// found int[]"; control bytes quoted from the input reach no terminal raw.
TEST(SceneReader, OutOfRangeIntegersAndControlBytesAreSpelledOut) {
    auto r = read(std::string(R"(
def BasisCurves "wide"
{
    int[] curveVertexCounts = [4, 99999999999]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0)]
}
def BasisCurves "bell"
{
    token visibility = "in)") + "\x07\x1b[2J" + R"(visible"
)" + kOneCurve + R"(
}
)");
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/wide.curveVertexCounts: element 1 is 99999999999, beyond a 32-bit int "
                                            "(at most 2147483647); prim skipped"}))
        << allWarnings(r->diagnostics);
    for (const Diagnostic& d : r->diagnostics.warnings())
        for (char c : d.where + d.message) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20) << d.message;
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/bell.visibility", "\\x07\\x1b[2J"})) << allWarnings(r->diagnostics);
}

TEST(SceneReader, MeshPrim) {
    auto r = read(R"(
def Mesh "ground"
{
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
    point3f[] points = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
    uniform token subdivisionScheme = "none"
    color3f[] primvars:displayColor = [(0.2, 0.3, 0.4)]
    normal3f[] normals = [(0, 1, 0), (0, 1, 0), (0, 1, 0), (0, 1, 0)] (
        interpolation = "faceVarying"
    )
}
def Mesh "tagged"
{
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 3, 2, 1]
    point3f[] points = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
    uniform token orientation = "leftHanded"
    uniform token interpolateBoundary = "edgeOnly"
    uniform token faceVaryingLinearInterpolation = "all"
    uniform token triangleSubdivisionRule = "smooth"
    int[] holeIndices = [0]
    int[] cornerIndices = [1]
    float[] cornerSharpnesses = [2.5]
    int[] creaseIndices = [0, 1, 2]
    int[] creaseLengths = [3]
    float[] creaseSharpnesses = [10]
    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (
        interpolation = "faceVarying"
    )
    int[] primvars:displayColor:indices = [0, 1, 1, 0]
}
def Mesh "smooth"
{
    uniform token purpose = "guide"
}
)");
    ASSERT_EQ(r->scene.meshes().size(), 2u);
    const MeshPrim& tagged = *r->scene.meshes().at("/tagged").prim;
    EXPECT_EQ(tagged.subdivisionScheme, "catmullClark");
    EXPECT_EQ(tagged.orientation, "leftHanded");
    EXPECT_EQ(tagged.interpolateBoundary, "edgeOnly");
    EXPECT_EQ(tagged.faceVaryingLinearInterpolation, "all");
    EXPECT_EQ(tagged.triangleSubdivisionRule, "smooth");
    EXPECT_EQ(tagged.holeIndices, std::vector<int>{0});
    EXPECT_EQ(tagged.cornerIndices, std::vector<int>{1});
    EXPECT_EQ(tagged.cornerSharpnesses, std::vector<float>{2.5f});
    EXPECT_EQ(tagged.creaseIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(tagged.creaseLengths, std::vector<int>{3});
    EXPECT_EQ(tagged.creaseSharpnesses, std::vector<float>{10.0f});
    EXPECT_EQ(tagged.refineLevel, -1);
    ASSERT_EQ(tagged.primvars.count("displayColor"), 1u);
    EXPECT_EQ(tagged.primvars.at("displayColor").interpolation, Interpolation::FaceVarying);
    EXPECT_EQ(tagged.primvars.at("displayColor").indices, (std::vector<int>{0, 1, 1, 0}));
    const MeshPrim& mesh = *r->scene.meshes().at("/ground").prim;
    EXPECT_EQ(mesh.faceVertexCounts, std::vector<int>{4});
    EXPECT_EQ(mesh.faceVertexIndices, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(mesh.points.size(), 4u);
    EXPECT_EQ(mesh.subdivisionScheme, "none");
    EXPECT_EQ(mesh.sourceFile, r->stage->rootLayerPath());
    ASSERT_EQ(mesh.primvars.count("displayColor"), 1u);
    ASSERT_EQ(mesh.primvars.count("normals"), 1u);
    EXPECT_EQ(mesh.primvars.at("normals").interpolation, Interpolation::FaceVarying);
}

TEST(SceneReader, StageInfo) {
    auto r = read(R"((
    upAxis = "Z"
    metersPerUnit = 1
    startTimeCode = 1
    endTimeCode = 48
    framesPerSecond = 30
)
)");
    const StageInfo& info = r->scene.info();
    EXPECT_EQ(info.upAxis, UpAxis::Z);
    EXPECT_DOUBLE_EQ(info.metersPerUnit, 1.0);
    EXPECT_DOUBLE_EQ(info.startTimeCode, 1.0);
    EXPECT_DOUBLE_EQ(info.endTimeCode, 48.0);
    // Only framesPerSecond authored: USD uses it for timeCodesPerSecond.
    EXPECT_DOUBLE_EQ(info.timeCodesPerSecond, 30.0);
    EXPECT_EQ(info.sourceFile, r->stage->rootLayerPath());

    auto both = read(R"((
    timeCodesPerSecond = 24
    framesPerSecond = 12
)
)");
    EXPECT_DOUBLE_EQ(both->scene.info().timeCodesPerSecond, 24.0);
    EXPECT_EQ(both->scene.info().upAxis, UpAxis::Y);
    EXPECT_DOUBLE_EQ(both->scene.info().metersPerUnit, 0.01);
}

TEST(SceneReader, UnsupportedGprimsAreReportedOnce) {
    auto r = read(R"(
def Sphere "a"
{
}
def Sphere "b"
{
}
def NurbsCurves "c"
{
}
def Xform "x"
{
}
)");
    EXPECT_EQ(r->diagnostics.warningCount(), 2u) << allWarnings(r->diagnostics);
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/a", "Sphere"}));
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/c", "NurbsCurves"}));
}

TEST(SceneReader, ReadSceneFileOpensAndReads) {
    Scene scene;
    Diagnostics diagnostics;
    EXPECT_THROW(readSceneFile("/nonexistent/hair.usda", 0.0, scene, diagnostics), InputError);
}

TEST(SceneReader, UnauthoredLightInputsTakeTheUsdLuxFallbacks) {
    auto r = read(R"(
def DistantLight "sun"
{
}
def SphereLight "bulb"
{
}
)");
    EXPECT_FLOAT_EQ(r->scene.lights().at("/sun").prim->intensity, 50000.0f);
    EXPECT_FLOAT_EQ(r->scene.lights().at("/bulb").prim->intensity, 1.0f);
    EXPECT_FLOAT_EQ(r->scene.lights().at("/bulb").prim->exposure, 0.0f);
}

TEST(SceneReader, MaterialBindingsAndPreviewSurfaceInputs) {
    // As usdcat writes UsdShade: an all-purpose binding on an ancestor, a
    // preview binding that wins over it, interface inputs and a primvar reader.
    auto r = read(R"(
def Xform "World" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    rel material:binding = </World/Looks/red>

    def BasisCurves "inherits"
    {
        int[] curveVertexCounts = [2]
        point3f[] points = [(0, 0, 0), (1, 0, 0)]
    }

    def BasisCurves "preview" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        int[] curveVertexCounts = [2]
        point3f[] points = [(0, 0, 0), (1, 0, 0)]
        rel material:binding = </World/Looks/red>
        rel material:binding:preview = </World/Looks/fromPrimvar>
    }

    def BasisCurves "broken" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {
        int[] curveVertexCounts = [2]
        point3f[] points = [(0, 0, 0), (1, 0, 0)]
        rel material:binding = </World/Looks>
    }

    def Scope "Looks"
    {
        def Material "red"
        {
            color3f inputs:hairColor = (0.8, 0.1, 0.05)
            token outputs:surface.connect = </World/Looks/red/Surface.outputs:surface>

            def Shader "Surface"
            {
                uniform token info:id = "UsdPreviewSurface"
                color3f inputs:diffuseColor.connect = </World/Looks/red.inputs:hairColor>
                float inputs:opacity = 0.5
                token outputs:surface
            }
        }

        def Material "fromPrimvar"
        {
            token outputs:surface.connect = </World/Looks/fromPrimvar/Surface.outputs:surface>

            def Shader "Surface"
            {
                uniform token info:id = "UsdPreviewSurface"
                color3f inputs:diffuseColor.connect = </World/Looks/fromPrimvar/Reader.outputs:result>
                token outputs:surface
            }

            def Shader "Reader"
            {
                uniform token info:id = "UsdPrimvarReader_float3"
                float3 inputs:fallback = (0, 0, 1)
                string inputs:varname = "hairColor"
                float3 outputs:result
            }
        }
    }
}
)");
    const CurvesPrim* inherits = r->scene.findCurves("/World/inherits");
    ASSERT_NE(inherits, nullptr);
    EXPECT_EQ(inherits->materialBinding, "/World/Looks/red");
    EXPECT_EQ(r->scene.findCurves("/World/preview")->materialBinding, "/World/Looks/fromPrimvar");
    EXPECT_EQ(r->scene.findCurves("/World/broken")->materialBinding, "");
    EXPECT_TRUE(hasWarning(r->diagnostics, {"/World/broken.material:binding: /World/Looks is a Scope, not a Material"}));

    const auto* red = r->scene.findMaterial("/World/Looks/red");
    ASSERT_NE(red, nullptr);
    EXPECT_TRUE(red->prim->isPreviewSurface());
    EXPECT_EQ(red->prim->diffuseColor.source, MaterialInput::Source::Value);
    EXPECT_EQ(red->prim->diffuseColor.value, (std::vector<float>{0.8f, 0.1f, 0.05f}));
    EXPECT_EQ(red->prim->opacity.value, std::vector<float>{0.5f});

    const auto* fromPrimvar = r->scene.findMaterial("/World/Looks/fromPrimvar");
    ASSERT_NE(fromPrimvar, nullptr);
    EXPECT_EQ(fromPrimvar->prim->diffuseColor.source, MaterialInput::Source::Primvar);
    EXPECT_EQ(fromPrimvar->prim->diffuseColor.primvar, "hairColor");
    EXPECT_EQ(fromPrimvar->prim->diffuseColor.value, (std::vector<float>{0.0f, 0.0f, 1.0f}));
    EXPECT_EQ(fromPrimvar->prim->opacity.value, std::vector<float>{1.0f}) << "UsdPreviewSurface's default";
    EXPECT_EQ(r->diagnostics.warningCount(), 1u);
}

TEST(SceneReader, MaterialsWithTexturesOrOtherShadersAreReadForWhatTheyAre) {
    auto r = read(R"(
def BasisCurves "hair" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    int[] curveVertexCounts = [2]
    point3f[] points = [(0, 0, 0), (1, 0, 0)]
    rel material:binding = </textured>
}

def BasisCurves "other" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    int[] curveVertexCounts = [2]
    point3f[] points = [(0, 0, 0), (1, 0, 0)]
    rel material:binding = </marschner>
}

def Material "textured"
{
    token outputs:surface.connect = </textured/Surface.outputs:surface>

    def Shader "Surface"
    {
        uniform token info:id = "UsdPreviewSurface"
        color3f inputs:diffuseColor.connect = </textured/Texture.outputs:rgb>
        token outputs:surface
    }

    def Shader "Texture"
    {
        uniform token info:id = "UsdUVTexture"
        asset inputs:file = @hair.png@
        float3 outputs:rgb
    }
}

def Material "marschner"
{
    token outputs:ri:surface.connect = </marschner/Hair.outputs:out>

    def Shader "Hair"
    {
        uniform token info:id = "PxrMarschnerHair"
        token outputs:out
    }
}
)");
    const auto* textured = r->scene.findMaterial("/textured");
    ASSERT_NE(textured, nullptr);
    EXPECT_EQ(textured->prim->diffuseColor.source, MaterialInput::Source::Unsupported);
    EXPECT_EQ(textured->prim->diffuseColor.connectedTo, "UsdUVTexture");
    const auto* other = r->scene.findMaterial("/marschner");
    ASSERT_NE(other, nullptr);
    EXPECT_EQ(other->prim->surfaceShaderId, "") << "no universal surface";
    EXPECT_FALSE(other->prim->isPreviewSurface());
    EXPECT_TRUE(r->diagnostics.warnings().empty());
}

// Hydra hands the plugin no colour space, so the embedded reader takes every
// authored colour as linear Rec.709 too, and says so where a stage claims
// another space rather than dropping the claim silently.
TEST(SceneReader, ColourSpaceMetadataOtherThanLinearRec709IsNamedAndNotApplied) {
    auto result = read(R"(
def BasisCurves "Hair" {
    int[] curveVertexCounts = [4]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0)]
    color3f[] primvars:displayColor = [(0.5, 0.2, 0.1)] (colorSpace = "ACEScg")
}
def BasisCurves "Linear" {
    int[] curveVertexCounts = [4]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (0, 3, 0)]
    color3f[] primvars:displayColor = [(0.5, 0.2, 0.1)] (colorSpace = "lin_rec709")
}
def DistantLight "Sun" {
    color3f inputs:color = (1, 0.9, 0.8) (colorSpace = "sRGB")
}
)");
    EXPECT_TRUE(hasWarning(result->diagnostics, {"/Hair.primvars:displayColor", "colorSpace 'ACEScg' is not applied",
                                                 "linear Rec.709"}))
        << allWarnings(result->diagnostics);
    EXPECT_TRUE(hasWarning(result->diagnostics, {"/Sun.inputs:color", "colorSpace 'sRGB' is not applied"}))
        << allWarnings(result->diagnostics);
    EXPECT_EQ(result->diagnostics.warnings().size(), 2u) << allWarnings(result->diagnostics);
    // The values stay as authored.
    const Primvar& color = result->scene.curves().at("/Hair").prim->primvars.at("displayColor");
    ASSERT_EQ(color.values.size(), 3u);
    EXPECT_FLOAT_EQ(color.values[0], 0.5f);
}
