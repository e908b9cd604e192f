#pragma once
// A small scene that exercises every part of a frame that can be stopped or
// simplified: wavy translucent catmullRom strands in several prims (bin
// sorting, coverage), two shadow-casting lights and three that do not (deep
// opacity maps; three light batches at lightsPerPass=2), seen by a
// perspective camera that can orbit the tuft.

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/Scene.h"

namespace hdhair::testscenes {

// `curves` wavy strands of 6 points rising from a disk of radius 0.5 to a
// height of about 2, 0.02 wide, half opaque; `seed` shifts every point so
// that two prims differ.
inline CurvesPrim tuftStrands(const std::string& path, int primId, int curves, float seed) {
    CurvesPrim prim;
    prim.path = path;
    prim.primId = primId;
    prim.type = CurveType::Cubic;
    prim.basis = CurveBasis::CatmullRom;
    for (int c = 0; c < curves; ++c) {
        // A low-discrepancy spiral over the disk.
        const float angle = 2.39996f * float(c) + seed;
        const float radius = 0.5f * std::sqrt((float(c) + 0.5f) / float(curves));
        const float x = radius * std::cos(angle), z = radius * std::sin(angle);
        prim.curveVertexCounts.push_back(6);
        for (int p = 0; p < 6; ++p) {
            const float t = float(p) / 5.0f;
            prim.points.push_back({x + 0.15f * std::sin(6.0f * t + angle), 2.0f * t, z + 0.15f * std::cos(5.0f * t + seed)});
        }
    }
    Primvar widths;
    widths.name = "widths";
    widths.values = {0.02f};
    prim.primvars["widths"] = widths;
    Primvar opacity;
    opacity.name = "displayOpacity";
    opacity.values = {0.5f};
    prim.primvars["displayOpacity"] = opacity;
    Primvar color;
    color.name = "displayColor";
    color.tupleSize = 3;
    color.values = {0.6f, 0.4f + 0.1f * seed, 0.2f};
    prim.primvars["displayColor"] = color;
    return prim;
}

inline LightPrim distantLight(const std::string& path, float degreesAboutY, float degreesDown, bool casts) {
    LightPrim light;
    light.path = path;
    light.type = LightType::Distant;
    light.intensity = 2.0f;
    light.shadowEnable = casts;
    light.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(double(degreesAboutY)), glm::dvec3(0, 1, 0)) *
                           glm::rotate(glm::dmat4(1.0), glm::radians(-double(degreesDown)), glm::dvec3(1, 0, 0));
    return light;
}

// Three prims of `curvesPerPrim` strands and five lights, two casting.
inline Scene hairTuft(int curvesPerPrim) {
    Scene scene;
    scene.setCurves(tuftStrands("/tuft/a", 1, curvesPerPrim, 0.0f));
    scene.setCurves(tuftStrands("/tuft/b", 2, curvesPerPrim, 1.0f));
    scene.setCurves(tuftStrands("/tuft/c", 3, curvesPerPrim, 2.0f));
    scene.setLight(distantLight("/lights/key", 30.0f, 40.0f, true));
    scene.setLight(distantLight("/lights/fill", -70.0f, 20.0f, true));
    scene.setLight(distantLight("/lights/rim", 180.0f, 10.0f, false));
    scene.setLight(distantLight("/lights/top", 0.0f, 85.0f, false));
    scene.setLight(distantLight("/lights/low", 90.0f, -10.0f, false));
    return scene;
}

// A 50 mm camera 7 units from the tuft's middle, turned `degrees` about
// the vertical axis through it, `width` pixels wide.
inline CameraView tuftCamera(double degrees, int width) {
    CameraPrim camera;
    camera.clippingRange = {0.5f, 100.0f};
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.0, 0.0)) *
                            glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0, 1, 0)) *
                            glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 7.0));
    return cameraViewFromPrim(camera, width);
}

}  // namespace hdhair::testscenes
