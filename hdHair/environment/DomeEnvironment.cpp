#include "hdHair/environment/DomeEnvironment.h"

#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "hdHair/environment/LatlongDirections.h"

namespace hdhair {

namespace {

bool isLatlongFormat(const std::string& format) { return format == "automatic" || format == "latlong"; }

}  // namespace

DomeEnvironment domeEnvironment(const LightPrim& dome, const glm::vec3& radianceScale,
                                const DomeFitSettings& settings, Diagnostics& diagnostics,
                                DomeTextureFitCache& cache) {
    if (dome.type != LightType::Dome) throw std::invalid_argument("domeEnvironment: " + dome.path + " is not a dome");
    DomeEnvironment environment;
    environment.lightPath = dome.path;
    environment.uniformRadiance = radianceScale;
    if (dome.textureFile.empty()) return environment;
    if (!isLatlongFormat(dome.textureFormat)) {
        diagnostics.warn(dome.path,
                         fmt::format("{}.inputs:texture:format: '{}' is not supported (hdHair reads latlong maps: "
                                     "automatic, latlong); '{}' is not used and the dome is lit uniformly",
                                     dome.path, dome.textureFormat, dome.textureFile));
        return environment;
    }
    const std::shared_ptr<const DomeTextureFit> fit = cache.latlongFit(dome.textureFile, settings);
    const std::string where = dome.path + ".inputs:texture:file";
    if (!fit->error.empty()) {
        diagnostics.warn(dome.path, fmt::format("{}: {}; the dome is lit uniformly, untextured", where, fit->error));
        return environment;
    }
    if (fit->repairedTexels > 0)
        diagnostics.warn(dome.path, fmt::format("{}: {} texel(s) of '{}' have a NaN, infinite or negative channel; those "
                                            "channels are read as 0",
                                            where, fit->repairedTexels, dome.textureFile));
    environment.uniformRadiance = glm::vec3(0.0f);
    environment.fitError = fit->fit.relativeError;
    environment.srbfs.reserve(fit->fit.srbfs.size());
    for (const Srbf& lobe : fit->fit.srbfs) {
        Srbf world = lobe;
        world.lobe.centre = domeLightDirectionToWorld(dome.worldTransform, lobe.lobe.centre);
        world.amplitude = lobe.amplitude * radianceScale;
        environment.srbfs.push_back(world);
    }
    return environment;
}

glm::vec3 environmentRadiance(const DomeEnvironment& environment, const glm::vec3& worldDirection) {
    return environment.uniformRadiance + srbfRadiance(environment.srbfs, worldDirection);
}

}  // namespace hdhair
