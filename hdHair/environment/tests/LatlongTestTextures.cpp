#include "hdHair/environment/tests/LatlongTestTextures.h"

#include <atomic>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>
#include <unistd.h>

#include "hdHair/environment/LatlongDirections.h"

namespace hdhair::test {

namespace fs = std::filesystem;

TemporaryFolder::TemporaryFolder() {
    static std::atomic<int> counter{0};
    const fs::path folder = fs::temp_directory_path() / ("hdhair_environment_" + std::to_string(::getpid()) + "_" +
                                                         std::to_string(counter++));
    fs::create_directories(folder);
    path_ = fs::canonical(folder).string();
}

TemporaryFolder::~TemporaryFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
}

std::string TemporaryFolder::path(const std::string& name) const { return (fs::path(path_) / name).string(); }

std::vector<float> latlongPixels(int width, int height, const std::function<glm::vec3(const glm::vec3&)>& radiance) {
    std::vector<float> pixels;
    pixels.reserve(size_t(width) * size_t(height) * 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::vec3 value = radiance(latlongDirection((float(x) + 0.5f) / float(width),
                                                              (float(y) + 0.5f) / float(height)));
            pixels.insert(pixels.end(), {value.r, value.g, value.b});
        }
    }
    return pixels;
}

void writeTestImage(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels,
                    OIIO::TypeDesc format, int tileSize) {
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    if (!output) throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());
    OIIO::ImageSpec spec(width, height, channels, format);
    if (tileSize > 0) {
        spec.tile_width = tileSize;
        spec.tile_height = tileSize;
    }
    if (!output->open(path, spec) ||
        !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !output->close())
        throw std::runtime_error("cannot write '" + path + "': " + output->geterror());
}

glm::vec3 proceduralSky(const glm::vec3& direction, const glm::vec3& sun) {
    const glm::vec3 sky = direction.y >= 0.0f ? glm::vec3(0.3f, 0.5f, 1.0f) * (0.4f + 0.6f * direction.y)
                                              : glm::vec3(0.10f, 0.08f, 0.05f);
    return sky + glm::vec3(40.0f, 36.0f, 30.0f) * std::exp(300.0f * (glm::dot(direction, sun) - 1.0f));
}

}  // namespace hdhair::test
