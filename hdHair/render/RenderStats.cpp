#include "hdHair/render/RenderStats.h"

#include <cmath>

namespace hdhair {

nlohmann::json RenderStats::toJson() const {
    nlohmann::json json;
    json["image"] = {{"width", imageWidth}, {"height", imageHeight}};
    json["supersampling"] = supersampling;
    json["camera"] = camera;
    // UsdTimeCode's special times have no JSON number: name them.
    json["time"] = std::isnan(time) ? nlohmann::json("default")
                   : std::isinf(time) ? nlohmann::json(time < 0 ? "earliest" : "latest")
                                      : nlohmann::json(time);
    json["prims"] = {{"basisCurves", curvesPrims}, {"meshes", meshPrims}, {"lights", lights}};
    json["curves"] = curves;
    json["segments"] = segments;
    json["authoredPoints"] = authoredPoints;
    json["meshTriangles"] = meshTriangles;
    json["strandTriangles"] = strandTriangles;
    json["lightViewSpans"] = {{"straight", lightViewStraightSpans},
                              {"tessellated", lightViewTessellatedSpans},
                              {"compute", lightViewComputeSpans}};
    nlohmann::json passList = nlohmann::json::array();
    for (const PassTiming& pass : passes) passList.push_back({{"name", pass.name}, {"milliseconds", pass.milliseconds}});
    json["passes"] = passList;
    json["totalMilliseconds"] = totalMilliseconds;
    json["gl"] = glRenderer;
    json["glDevice"] = glDevice;
    json["settings"] = settings;
    json["settingOrigins"] = settingOrigins;
    json["plan"] = plan;
    if (!abandonedPlans.empty()) json["abandonedPlans"] = abandonedPlans;
    json["warnings"] = warnings;
    json["transparency"] = transparency;
    json["strandRaster"] = strandRaster;
    json["lightPasses"] = lightPasses;
    json["preparedPrims"] = preparedPrims;
    json["preparedMeshes"] = preparedMeshes;
    json["uploadedSegments"] = uploadedSegments;
    json["passTiming"] = passTiming;
    json["drawBatching"] = drawBatching;
    json["strandShaders"] = strandShaders;
    json["shadowMapsRebuilt"] = shadowMapsRebuilt;
    json["shadowMapsKept"] = shadowMapsKept;
    json["shadowMaps"] = shadowMaps;
    json["multipleScattering"] = multipleScattering;
    // Each use, and their total: what the frame's memory is made of.
    auto byUse = [](const std::map<std::string, uint64_t>& uses) {
        nlohmann::json memory = nlohmann::json::object();
        uint64_t total = 0;
        for (const auto& [use, bytes] : uses) {
            memory[use] = bytes;
            total += bytes;
        }
        memory["total"] = total;
        return memory;
    };
    json["gpuMemory"] = byUse(gpuBytes);
    json["cpuMemory"] = byUse(cpuBytes);
    if (fragments > 0) json["fragments"] = fragments;
    if (fragments > 0 && expectedFragments > 0) json["expectedFragments"] = expectedFragments;
    if (listTiles > 0) json["fragmentListTiles"] = {{"resolved", resolvedListTiles}, {"inImage", listTiles}};
    if (!fallback.empty()) json["fallback"] = fallback;
    return json;
}

}  // namespace hdhair
