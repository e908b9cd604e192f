#pragma once
// What a render did, for --stats FILE.json and --verbose: what was drawn,
// the plan, each pass's time, and the settings in effect.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hdhair {

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

struct RenderStats {
    int imageWidth = 0, imageHeight = 0;  // the output's size (with supersampling, not the samples')
    int supersampling = 1;                 // N: N x N samples per pixel (SupersampleResolve.h)
    std::string camera;           // prim path, or "framing camera"
    double time = 0.0;            // time code; NaN: UsdTimeCode::Default(), -inf: EarliestTime()
    size_t curvesPrims = 0, meshPrims = 0, lights = 0;
    uint64_t curves = 0, segments = 0;
    uint64_t authoredPoints = 0;  // control vertices the drawn curves prims author (their points)
    uint64_t meshTriangles = 0;   // of the meshes drawn, after refinement
    // Triangles the colour passes over the strands drew, every light batch's
    // (as tessellated, culled spans excluded; 0 for exact transparency,
    // which draws its own way).
    uint64_t strandTriangles = 0;
    // Spans the light views that draw strand lines listed this frame
    // (shadowStrandLines=drawn, gl/LightViewSpans.h): drawn as plain lines,
    // one segment each, and drawn through the tessellator.
    uint64_t lightViewStraightSpans = 0, lightViewTessellatedSpans = 0;
    // Spans the light views gave the compute rasteriser (gl/LightViewRaster.h).
    uint64_t lightViewComputeSpans = 0;
    size_t preparedMeshes = 0;    // meshes refined and triangulated this frame (changed ones only)
    std::vector<PassTiming> passes;
    double totalMilliseconds = 0.0;
    std::string glRenderer;
    std::string glDevice;         // where the context was made: "EGL surfaceless (Mesa)", "EGL device 0 (...)"
    nlohmann::json settings;
    nlohmann::json settingOrigins;  // what chose each setting (SettingOrigins.h)
    nlohmann::json plan;
    // The plans made before `plan` and given up, each with its reason
    // (RenderResult::abandonedPlans); empty when the first plan ran.
    nlohmann::json abandonedPlans = nlohmann::json::array();
    size_t warnings = 0;
    std::string transparency;     // the path taken: opaque, binSorted, exact or unsorted
    std::string strandRaster;     // who rasterised the camera's strands: hardware, compute, or compute+hardware (auto, per prim)
    uint64_t fragments = 0;       // strand fragments, when known (exact transparency and the compute rasteriser count them)
    // The plan's estimate of them, which sizes a first frame's list storage
    // (StrandRasterPlan::expectedFragments; 0 unknown).
    uint64_t expectedFragments = 0;
    // With fragment lists: the 16-pixel tiles of the image that held
    // fragments (the resolve covers only those), of all the image's tiles.
    uint64_t resolvedListTiles = 0, listTiles = 0;
    std::string fallback;         // what replaced the requested path, and why ("" when nothing did)
    size_t lightPasses = 1;       // passes over the strands, one per batch of at most lightsPerPass lights
    size_t preparedPrims = 0;     // curves prims prepared for this frame (only new and changed ones)
    uint64_t uploadedSegments = 0;  // strand segments sent to the GPU this frame (only changed prims)
    std::string passTiming;       // how passes were timed (the passTimings setting and the driver)
    std::string drawBatching;     // how strand draws were cut (hdHair/gl/PatchBatching.h)
    // The strand programs the frame drew with, each by the shading it compiles
    // (hdHair/gl/ShadingFeatures.h describe(): "shade kajiyaKay deepOpacity"; the ids pass's "none").
    std::vector<std::string> strandShaders;
    // Shadow maps this frame: rebuilt, kept from an earlier frame, and per
    // shadow-casting light what happened and why ({"light", "map", "reason"};
    // map is "rebuilt", "kept" or "none").
    size_t shadowMapsRebuilt = 0, shadowMapsKept = 0;
    nlohmann::json shadowMaps = nlohmann::json::array();
    // Per hair material of the frame, its multiple scattering ({"material":
    // its index, "prims": how many prims, "prim": the first, "model",
    // "dualScattering": whether it runs, "gain", "reason"}).
    nlohmann::json multipleScattering = nlohmann::json::array();
    // Bytes of GL storage the renderer holds after the frame, by use
    // (hdHair/gl/GpuMemory.h): strandGeometry, drawOrder, frameTarget, ...
    std::map<std::string, uint64_t> gpuBytes;
    // Bytes of CPU memory the renderer holds for the strands beyond the parsed
    // stage, by use: preparedCurves and sortHashes (kept between frames),
    // hairParameterPoints, and the frame's drawOrder.
    std::map<std::string, uint64_t> cpuBytes;

    nlohmann::json toJson() const;
};

}  // namespace hdhair
