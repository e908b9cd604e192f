#pragma once
// Dome textures made by the tests themselves, written with OpenImageIO into
// a temporary folder: no image is committed, and every texel is known.

#include <functional>
#include <string>
#include <vector>

#include <OpenImageIO/typedesc.h>
#include <glm/vec3.hpp>

namespace hdhair::test {

// A fresh folder under the system's temporary folder, removed with the object.
class TemporaryFolder {
public:
    TemporaryFolder();
    ~TemporaryFolder();
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    std::string path(const std::string& name) const;

private:
    std::string path_;
};

// A width × height RGB image whose texel at each centre direction (in the
// dome's frame, LatlongDirections.h) is radiance(direction); rows top down.
std::vector<float> latlongPixels(int width, int height, const std::function<glm::vec3(const glm::vec3&)>& radiance);

// Writes `pixels` (width × height × channels, rows top down) to `path`, the
// format chosen by its extension, stored as `format`; tiled when tileSize > 0.
void writeTestImage(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels,
                    OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT, int tileSize = 0);

// A clear sky over dark ground with a small bright sun towards `sun` (unit).
glm::vec3 proceduralSky(const glm::vec3& direction, const glm::vec3& sun);

}  // namespace hdhair::test
