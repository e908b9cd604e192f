// Multiple scattering on the GPU (shaders/include/dualScattering.glsl) as
// the CPU reference says (hdHair/shading/DualScattering.h): a straight
// strand under one distant light, seen by an orthographic camera, so the
// tangent, eye and light at its centre pixel are known, unshadowed and
// behind an occluder of known opacity. Then multipleScattering=auto's
// decision as --stats reports it, black hair's frame unchanged by it, and
// the hard cases (docs/hard-cases.md). Against Cycles: testCyclesCalibration.

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "DistantLight.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"
#include "hdHair/shading/DualScattering.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/shading/MarschnerTables.h"

using namespace hdhair;
using namespace hdhair::testenv;

namespace {

Primvar constant(const std::string& name, std::vector<float> values) {
    const int tupleSize = int(values.size());
    return test::authoredPrimvar(name, Interpolation::Constant, tupleSize, std::move(values));
}

// A Marschner strand along +X at height y and depth z, `width` wide.
CurvesPrim strand(const std::string& path, glm::vec3 centre, float width, float melanin, float opacity = 1.0f) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2};
    prim.points = {centre + glm::vec3(-2.0f, 0.0f, 0.0f), centre + glm::vec3(2.0f, 0.0f, 0.0f)};
    prim.primvars["widths"] = constant("widths", {width});
    prim.primvars["displayColor"] = constant("displayColor", {0.5f, 0.5f, 0.5f});
    prim.primvars["hdHair:melanin"] = constant("hdHair:melanin", {melanin});
    if (opacity < 1.0f) prim.primvars["displayOpacity"] = constant("displayOpacity", {opacity});
    prim.shadingModel = "marschner";
    return prim;
}

CameraView camera() { return orthographicView(2.4, 64); }

RenderSettings settingsWith(const std::string& multipleScattering, const std::string& shadowMode = "off") {
    RenderSettings settings;
    settings.set("multipleScattering", multipleScattering);
    settings.set("shadowMode", shadowMode);
    return settings;
}

RenderResult renderScene(const Scene& scene, const RenderSettings& settings) {
    Diagnostics diagnostics;
    RenderResult result = sharedRenderer().render(scene, camera(), settings, diagnostics);
    for (const auto& warning : diagnostics.warnings()) ADD_FAILURE() << warning.where << ": " << warning.message;
    return result;
}

glm::vec3 pixel(const RenderResult& result, int x, int y) {
    return glm::vec3(result.color.at(x, y, 0), result.color.at(x, y, 1), result.color.at(x, y, 2));
}

HairMaterial materialOf(const CurvesPrim& prim, const RenderSettings& settings) {
    Diagnostics diagnostics;
    return hairMaterialFor(prim, prepareCurves(prim, diagnostics, hairParameterPrimvars()), settings, diagnostics);
}

// The CPU's centre pixel: light of irradiance 2 (distantLightFrom) from
// `towardsLight`, transmittance T, eye +Z, tangent +X.
glm::vec3 cpuCentre(const HairMaterial& material, glm::dvec3 towardsLight, float T) {
    const glm::vec3 t(1, 0, 0), e(0, 0, 1), l = glm::vec3(glm::normalize(towardsLight));
    MarschnerTables tables = buildMarschnerTables(material.marschner);
    glm::vec3 single = evaluateMarschnerTabled(t, l, e, material.marschner, tables).radiance();
    DualScatteringTable dual = buildDualScatteringTable(material.marschner, material.densities.backward);
    DualScatteringFibre fibre = sampleDualScatteringTable(dual, 1.0f);  // cos θ_o: the eye across the fibre
    return 2.0f * (T * single + evaluateDualScattering(t, l, e, material.marschner, fibre, T, material.densities));
}

const glm::dvec3 kLightDirections[] = {
    {0.0, 0.6, 1.0},    // in front, above
    {1.0, 0.2, 0.3},    // along the fibre, grazing
    {-0.5, -0.8, 0.2},  // from below
    {0.3, 0.1, -1.0},   // behind the strand: transmission
};

}  // namespace

// Unshadowed (T = 1): the local back scattering alone is added.
TEST(MultipleScattering, GpuMatchesTheCpuReferenceUnshadowed) {
    for (float melanin : {0.0f, 0.15f, 0.5f}) {
        for (const glm::dvec3& direction : kLightDirections) {
            SCOPED_TRACE(::testing::Message() << "melanin " << melanin << " light " << direction.x << ", "
                                              << direction.y << ", " << direction.z);
            CurvesPrim hair = strand("/hair", glm::vec3(0.0f), 0.5f, melanin);
            Scene scene;
            scene.setCurves(hair);
            scene.setLight(distantLightFrom(direction));
            const RenderSettings settings = settingsWith("dualScattering");
            const HairMaterial material = materialOf(hair, settings);
            ASSERT_TRUE(material.dualScattering);
            const glm::vec3 gpu = pixel(renderScene(scene, settings), 32, 32);
            const glm::vec3 cpu = cpuCentre(material, direction, 1.0f);
            const glm::vec3 single = pixel(renderScene(scene, settingsWith("off")), 32, 32);
            // As GpuMarschnerMatchesTheCpuTabledModel: the same half texels,
            // the GPU's bilinear weights 8 bits of fraction.
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 2e-3f + 0.02f * cpu[c]) << "channel " << c;
            // And it is added: the local term is never zero for these fibres.
            EXPECT_GT(gpu.x, single.x + 1e-4f);
        }
    }
}

// Behind a strand of opacity 0.5 that covers it in the light's view (and
// not in the camera's), reference shadows give T = exp(-0.5) exactly
// (testShadows, SlabTransmittance): the global term, T^(1 - a_f) - T, adds
// light that passed through the occluder.
TEST(MultipleScattering, GpuMatchesTheCpuReferenceBehindAnOccluder) {
    const glm::dvec3 towardsLight(0.0, 0.6, 1.0);
    const glm::vec3 l = glm::vec3(glm::normalize(towardsLight));
    for (float melanin : {0.0f, 0.15f}) {
        SCOPED_TRACE(::testing::Message() << "melanin " << melanin);
        CurvesPrim hair = strand("/hair", glm::vec3(0.0f), 0.5f, melanin);
        CurvesPrim occluder = strand("/occluder", 1.5f * l, 1.2f, melanin, 0.5f);
        Scene scene;
        scene.setCurves(hair);
        scene.setCurves(occluder);
        scene.setLight(distantLightFrom(towardsLight));
        // d_b everywhere, as the CPU's reference has it (the volume's local
        // term: TheLocalTermSendsBackWhatTheHairBehindHas).
        RenderSettings settings = settingsWith("dualScattering", "reference");
        settings.set("multipleScattering:localTerm", "constant");
        const HairMaterial material = materialOf(hair, settings);
        const glm::vec3 gpu = pixel(renderScene(scene, settings), 32, 32);
        const glm::vec3 cpu = cpuCentre(material, towardsLight, std::exp(-0.5f));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 2e-3f + 0.02f * cpu[c]) << "channel " << c;
        // Mutation: at T = 1 (as if the transmittance never reached the
        // term) the pixel would be far off.
        const glm::vec3 unshadowed = cpuCentre(material, towardsLight, 1.0f);
        EXPECT_GT(std::abs(unshadowed.x - gpu.x), 0.1f * gpu.x);
    }
}

// The local term from the density volume (multipleScattering:localTerm=
// densityVolume, the default with shadows on) sends back what the hair
// behind a fibre has. A blond fibre alone has none: it keeps under 5 % of
// the local back scattering d_b everywhere gives it (0.0 % measured: the
// march starts past its own density). The same fibre in front of twelve
// like it stacked along the light gets all of it, within 3 % (100.0 %).
// Light and eye along +Z, the front fibre unshadowed (T = 1): the pixel is
// its single scattering plus d_b f_back times the share sent back.
TEST(MultipleScattering, TheLocalTermSendsBackWhatTheHairBehindHas) {
    const glm::dvec3 towardsLight(0.0, 0.0, 1.0);
    std::vector<CurvesPrim> slab;
    for (int i = 1; i <= 12; ++i)
        slab.push_back(strand("/behind" + std::to_string(i), glm::vec3(0.0f, 0.0f, -0.1f * float(i)), 0.5f, 0.15f));
    struct Case {
        const char* name;
        std::vector<CurvesPrim> behind;
        double lowest, highest;  // the volume's local term over d_b everywhere's
    };
    for (const Case& c : {Case{"alone", {}, 0.0, 0.05}, Case{"before a slab", slab, 0.97, 1.03}}) {
        SCOPED_TRACE(c.name);
        Scene scene;
        scene.setCurves(strand("/front", glm::vec3(0.0f), 0.5f, 0.15f));
        for (const CurvesPrim& prim : c.behind) scene.setCurves(prim);
        scene.setLight(distantLightFrom(towardsLight));
        RenderSettings constant = settingsWith("dualScattering", "deepOpacity");
        constant.set("multipleScattering:localTerm", "constant");
        const RenderResult volume = renderScene(scene, settingsWith("dualScattering", "deepOpacity"));
        EXPECT_TRUE(volume.plan.isEnabled("densityVolume"));
        const glm::vec3 single = pixel(renderScene(scene, settingsWith("off", "deepOpacity")), 32, 32);
        const glm::vec3 everywhere = pixel(renderScene(scene, constant), 32, 32) - single;
        const glm::vec3 behind = pixel(volume, 32, 32) - single;
        for (int channel = 0; channel < 3; ++channel) {
            ASSERT_GT(everywhere[channel], 0.01f * single[channel]) << "d_b everywhere adds light, channel " << channel;
            const double share = behind[channel] / everywhere[channel];
            std::printf(
                "%s, channel %d: the volume's local term is %.3f of d_b "
                "everywhere's\n",
                c.name, channel, share);
            EXPECT_GE(share, c.lowest) << "channel " << channel;
            EXPECT_LE(share, c.highest) << "channel " << channel;
        }
    }
}

// auto: a black fibre's gain is under the bound and nothing runs (the frame
// is the one without multiple scattering, bit for bit); a blond fibre's is
// over it and it runs. --stats says which and why, per material.
TEST(MultipleScattering, AutoSkipsBlackHairAndRunsOnBlond) {
    Scene scene;
    scene.setCurves(strand("/black", glm::vec3(0.0f, 0.5f, 0.0f), 0.4f, 0.95f));
    scene.setCurves(strand("/blond", glm::vec3(0.0f, -0.5f, 0.0f), 0.4f, 0.15f));
    scene.setLight(distantLightFrom({0.0, 0.6, 1.0}));
    const RenderResult automatic = renderScene(scene, settingsWith("auto", "deepOpacity"));
    const RenderResult off = renderScene(scene, settingsWith("off", "deepOpacity"));
    const nlohmann::json stats = automatic.stats.toJson()["multipleScattering"];
    ASSERT_EQ(stats.size(), 2u) << stats.dump();
    for (const nlohmann::json& material : stats) {
        const bool blond = material["prim"] == "/blond";
        EXPECT_EQ(material["dualScattering"].get<bool>(), blond) << material.dump();
        EXPECT_EQ(material["gain"].get<float>() >= kMultipleScatteringBound, blond) << material.dump();
        EXPECT_NE(material["reason"].get<std::string>().find(blond ? "runs" : "skipped"), std::string::npos)
            << material.dump();
    }
    // Black hair alone: the frame is off's, bit for bit. Blond alone:
    // brighter, with d_b everywhere (alone, the volume finds no hair behind
    // it to send light back: TheLocalTermSendsBackWhatTheHairBehindHas).
    for (float melanin : {0.95f, 0.15f}) {
        Scene alone;
        alone.setCurves(strand("/hair", glm::vec3(0.0f), 0.4f, melanin));
        alone.setLight(distantLightFrom({0.0, 0.6, 1.0}));
        RenderSettings automaticEverywhere = settingsWith("auto", "deepOpacity");
        automaticEverywhere.set("multipleScattering:localTerm", "constant");
        const RenderResult withAuto = renderScene(alone, automaticEverywhere);
        const RenderResult withOff = renderScene(alone, settingsWith("off", "deepOpacity"));
        if (melanin > 0.5f) {
            EXPECT_EQ(withAuto.color.pixels, withOff.color.pixels);
        } else {
            EXPECT_GT(pixel(withAuto, 32, 32).x, 1.05f * pixel(withOff, 32, 32).x);
        }
    }
    // The strand pass's reason names both decisions (--explain).
    const std::string plan = automatic.plan.describe();
    EXPECT_NE(plan.find("multiple scattering on /black: auto"), std::string::npos) << plan;
    EXPECT_NE(plan.find("multiple scattering on /blond: auto"), std::string::npos) << plan;
}

// Under a textured dome every SRBF lobe is a light of its own (its
// irradiance from its centre, its width added to the spreads): the strand
// programs compile dual scattering with the SRBF lights, and the blond
// strand gains light (d_b everywhere: alone, it has no hair behind it),
// finite everywhere.
TEST(MultipleScattering, TexturedDomeLobesAddMultipleScattering) {
    Scene scene;
    scene.setCurves(strand("/hair", glm::vec3(0.0f), 0.5f, 0.15f));
    LightPrim dome;
    dome.path = "/dome";
    dome.type = LightType::Dome;
    dome.textureFile = std::string(HDHAIR_SOURCE_DIR) + "/examples/dome_sky.exr";
    dome.textureFormat = "latlong";
    scene.setLight(dome);
    RenderSettings everywhere = settingsWith("dualScattering", "deepOpacity");
    everywhere.set("multipleScattering:localTerm", "constant");
    const RenderResult dual = renderScene(scene, everywhere);
    const RenderResult off = renderScene(scene, settingsWith("off", "deepOpacity"));
    bool compiled = false;
    for (const std::string& shader : dual.stats.strandShaders)
        compiled = compiled || (shader.find("dualScattering") != std::string::npos &&
                                shader.find("srbfLights") != std::string::npos);
    EXPECT_TRUE(compiled);
    for (float value : dual.color.pixels) ASSERT_TRUE(std::isfinite(value));
    EXPECT_GT(pixel(dual, 32, 32).x, 1.05f * pixel(off, 32, 32).x);
}

// Kajiya-Kay and flat prims never get it, whatever the setting.
TEST(MultipleScattering, KajiyaKayAndFlatPrimsAreNotGivenIt) {
    for (const char* model : {"kajiyaKay", "flat"}) {
        CurvesPrim hair = strand("/hair", glm::vec3(0.0f), 0.5f, 0.15f);
        hair.shadingModel = model;
        const HairMaterial material = materialOf(hair, settingsWith("dualScattering"));
        EXPECT_FALSE(material.dualScattering) << model;
        EXPECT_NE(material.multipleScatteringReason.find("no multiple scattering"), std::string::npos);
    }
}

// Hard cases: zero absorption, absorption at 1e6, one isolated fibre (no
// neighbours: only the local term, bounded), an untextured dome (its
// uniform response and d_b A_b), and a dense opaque stack under deep
// opacity maps: every pixel finite, none negative.
TEST(MultipleScattering, HardCasesStayFinite) {
    struct Case {
        const char* name;
        std::vector<CurvesPrim> prims;
        bool dome;
        std::string shadowMode;
    };
    std::vector<CurvesPrim> stack;
    for (int i = 0; i < 12; ++i)
        stack.push_back(strand("/stack" + std::to_string(i), glm::vec3(0.0f, 0.0f, -0.05f * float(i)), 0.5f, 0.0f));
    CurvesPrim zero = strand("/zero", glm::vec3(0.0f), 0.5f, 0.0f);
    zero.primvars["hdHair:absorption"] = constant("hdHair:absorption", {0.0f, 0.0f, 0.0f});
    CurvesPrim huge = strand("/huge", glm::vec3(0.0f), 0.5f, 0.0f);
    huge.primvars["hdHair:absorption"] = constant("hdHair:absorption", {1e6f, 1e6f, 1e6f});
    const std::vector<Case> cases = {{"zero absorption", {zero}, false, "deepOpacity"},
                                     {"absorption 1e6", {huge}, false, "deepOpacity"},
                                     {"isolated fibre", {strand("/one", glm::vec3(0.0f), 0.02f, 0.15f)}, false, "deepOpacity"},
                                     {"untextured dome", {zero}, true, "deepOpacity"},
                                     {"opaque stack", stack, false, "deepOpacity"}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        Scene scene;
        for (const CurvesPrim& prim : c.prims) scene.setCurves(prim);
        if (c.dome) {
            LightPrim dome;
            dome.path = "/dome";
            dome.type = LightType::Dome;
            scene.setLight(dome);
        } else {
            scene.setLight(distantLightFrom({0.2, 0.6, -1.0}));
        }
        const RenderResult result = renderScene(scene, settingsWith("dualScattering", c.shadowMode));
        float brightest = 0.0f;
        for (float value : result.color.pixels) {
            ASSERT_TRUE(std::isfinite(value));
            ASSERT_GE(value, 0.0f);
            brightest = std::max(brightest, value);
        }
        // Irradiance 2 (or a dome of radiance 1): a white fibre's single and
        // multiple scattering together stay within a few times that.
        EXPECT_LT(brightest, 20.0f);
    }
}
