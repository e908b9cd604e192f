#pragma once
// Which shadow maps a frame builds and which it keeps from an earlier frame,
// decided on the CPU before any GL work (the GL side, gl::ShadowMapStorage,
// holds one slot per light and does what this says).
//
// A light's map is rebuilt only when something it depends on changed:
//   - it is new to the renderer, or its slot storage grew;
//   - its light view (ShadowLightView: the light's position or direction,
//     and the casters' bounds it is fitted to; the camera light's view
//     follows the camera, so its map does too), or its meshes' view;
//   - the casters: any change of the strands on the GPU (castersVersion);
//   - the shadow and tessellation settings (ShadowPlan's operator==).
// Intensity, colour and other shading-only edits keep the map. Otherwise
// the map is kept: a light view tessellates the strands by its own texels
// (ShadowPassUniforms.h), not the camera's pixels, so moving only the
// camera rebuilds nothing but the camera light's map.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hdHair/plan/ShadowLightView.h"
#include "hdHair/plan/ShadowPlanner.h"

namespace hdhair {

struct ShadowMapRequest {
    std::string key;            // the light's path, or "camera light"
    ShadowLightView view;       // valid
    bool followsCamera = false;  // the camera light
    // The view its meshes' depth is drawn from (PlannedShadow::meshView;
    // not valid without meshes): moving a mesh away from the hair moves it.
    ShadowLightView meshView;
};

struct ShadowMapDecision {
    int slot = 0;        // where gl::ShadowMapStorage holds it
    bool rebuild = true;
    std::string reason;  // "rebuilt: ..." or "kept: ..."
};

struct ShadowFrame {
    std::vector<ShadowMapDecision> maps;  // one per request, in order
    int capacity = 0;                     // slots the storage must hold
};

class ShadowMapCache {
public:
    // rebuildTogether: the maps share storage that cannot be rebuilt light by
    // light (shadowMode=reference's fragment pool): any rebuild rebuilds all.
    ShadowFrame update(const std::vector<ShadowMapRequest>& requests, const ShadowPlan& shadows,
                       uint64_t castersVersion, bool rebuildTogether);
    // Drops a light's map (it could not be built): the next frame builds it again.
    void forget(const std::string& key) { held_.erase(key); }

private:
    struct Held {
        int slot = 0;
        ShadowLightView view, meshView;
        ShadowPlan shape;  // what shaped it (its lights left out)
        uint64_t castersVersion = 0;
    };
    std::map<std::string, Held> held_;
    int capacity_ = 0;
};

}  // namespace hdhair
