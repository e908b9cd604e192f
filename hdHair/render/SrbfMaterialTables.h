#pragma once
// Which SRBF-convolution table each hair material reads under dome lighting
// (hdHair/plan/DomeLighting.h), and the tables' texels for the GPU
// (gl::SrbfTableTextures): a Marschner table keyed by the material's fibre
// parameters, a Kajiya-Kay table keyed by its shininess, each from
// SrbfTableCache (memory, then the cache directory: $HDHAIR_CACHE_DIR, ...;
// else built, about a second for Marschner), and each table's uniform-dome
// response (SrbfUniformDome.h). Materials with equal parameters share a
// table. Built only for frames with a dome: a stage without one never pays.
// Marschner materials whose absorption varies per curve or vertex read the
// table of their lobes apart at σ_a = 0 (MarschnerLobes), and the shader
// puts each fragment's absorption back per lobe (SrbfVaryingAbsorption.h);
// other varying parameters (η, α, β, Kajiya-Kay's) take their mean, the
// material's own.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "hdHair/gl/SrbfTableTextures.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/shading/SrbfTableCache.h"

namespace hdhair {

class Diagnostics;

// The most Marschner tables one texture holds side by side (2048 texels, GL's
// guaranteed 3-D size, over 32 ψ nodes a table); more distinct Marschner
// materials read the first one's table, with a warning.
constexpr size_t kMaxSrbfMarschnerTables = 64;

// Whether a material reads a MarschnerLobes table (above).
bool srbfAbsorbsPerFragment(const HairMaterial& material);

struct SrbfTableUpload {
    // Per material: x its table among its kind's, y its uniform-dome row.
    std::vector<glm::ivec2> materialTables;
    std::vector<gl::SrbfTableTexels> marschner, kajiyaKay;
    std::vector<std::vector<glm::vec3>> uniformRows;  // Marschner tables' rows, then Kajiya-Kay's
};

class SrbfMaterialTables {
public:
    explicit SrbfMaterialTables(std::string cacheDirectory = defaultSrbfCacheDirectory());

    // The texels stay valid while this object lives.
    SrbfTableUpload tablesFor(const std::vector<HairMaterial>& materials, Diagnostics& diagnostics);

private:
    struct Entry {
        std::shared_ptr<const SrbfConvolutionTable> table;
        std::vector<uint16_t> halfTexels;
        std::vector<glm::vec3> uniform;
    };
    const Entry& entryFor(const SrbfTableRequest& request, Diagnostics& diagnostics);

    SrbfTableCache cache_;
    std::map<std::string, Entry> entries_;  // by srbfTableKey; a map keeps the texels where they are
};

}  // namespace hdhair
