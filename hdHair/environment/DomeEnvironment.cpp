#include "hdHair/environment/DomeEnvironment.h"

#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "hdHair/base/InputError.h"
#include "hdHair/environment/LatlongDirections.h"
#include "hdHair/environment/LatlongTexture.h"

namespace hdhair {

namespace {

bool isLatlongFormat(const std::string& format) { return format == "automatic" || format == "latlong"; }

// Whether `dome` names a texture it can be lit by; warns when it names one
// in a layout hdHair does not read.
bool hasLatlongTexture(const LightPrim& dome, Diagnostics& diagnostics) {
    if (dome.textureFile.empty()) return false;
    if (isLatlongFormat(dome.textureFormat)) return true;
    diagnostics.warn(dome.path, fmt::format("{}.inputs:texture:format: '{}' is not supported (hdHair reads latlong maps: "
                                            "automatic, latlong); '{}' is not used and the dome is lit uniformly",
                                            dome.path, dome.textureFormat, dome.textureFile));
    return false;
}

void warnTextureUnused(const LightPrim& dome, const std::string& why, Diagnostics& diagnostics) {
    diagnostics.warn(dome.path,
                     fmt::format("{}.inputs:texture:file: {}; the dome is lit uniformly, untextured", dome.path, why));
}

void warnRepairedTexels(const LightPrim& dome, size_t repairedTexels, Diagnostics& diagnostics) {
    if (repairedTexels == 0) return;
    diagnostics.warn(dome.path, fmt::format("{}.inputs:texture:file: {} texel(s) of '{}' have a NaN, infinite or "
                                            "negative channel; those channels are read as 0",
                                            dome.path, repairedTexels, dome.textureFile));
}

}  // namespace

DomeEnvironment domeEnvironment(const LightPrim& dome, const glm::vec3& radianceScale,
                                const DomeFitSettings& settings, Diagnostics& diagnostics,
                                DomeTextureFitCache& cache) {
    if (dome.type != LightType::Dome) throw std::invalid_argument("domeEnvironment: " + dome.path + " is not a dome");
    DomeEnvironment environment;
    environment.lightPath = dome.path;
    environment.uniformRadiance = radianceScale;
    if (!hasLatlongTexture(dome, diagnostics)) return environment;
    const std::shared_ptr<const DomeTextureFit> fit = cache.latlongFit(dome.textureFile, settings);
    if (!fit->error.empty()) {
        warnTextureUnused(dome, fit->error, diagnostics);
        return environment;
    }
    warnRepairedTexels(dome, fit->repairedTexels, diagnostics);
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

DomeEnvironment sampledDomeEnvironment(const LightPrim& dome, const glm::vec3& radianceScale, int lightCount,
                                       Diagnostics& diagnostics) {
    if (dome.type != LightType::Dome)
        throw std::invalid_argument("sampledDomeEnvironment: " + dome.path + " is not a dome");
    DomeEnvironment environment;
    environment.lightPath = dome.path;
    RadianceGrid grid = uniformDomeGrid(radianceScale, kSampledDomeGridWidth, kSampledDomeGridHeight);
    if (hasLatlongTexture(dome, diagnostics)) {
        try {
            LatlongTextureRead read = readLatlongTexture(dome.textureFile, kSampledDomeGridWidth, kSampledDomeGridHeight);
            warnRepairedTexels(dome, read.repairedTexels, diagnostics);
            grid = std::move(read.grid);
            for (glm::vec3& radiance : grid.radiance) radiance *= radianceScale;
        } catch (const InputError& error) {
            warnTextureUnused(dome, error.what(), diagnostics);
        }
    }
    environment.sampledLights = sampleDomeLights(grid, dome.worldTransform, lightCount);
    return environment;
}

glm::vec3 environmentRadiance(const DomeEnvironment& environment, const glm::vec3& worldDirection) {
    return environment.uniformRadiance + srbfRadiance(environment.srbfs, worldDirection);
}

}  // namespace hdhair
