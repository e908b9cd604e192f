#include "hdHair/render/SrbfMaterialTables.h"

#include <algorithm>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/shading/SrbfUniformDome.h"

namespace hdhair {

bool srbfAbsorbsPerFragment(const HairMaterial& material) {
    return material.model == ShadingModel::Marschner && (material.varies & kAbsorptionVaries) != 0;
}

SrbfMaterialTables::SrbfMaterialTables(std::string cacheDirectory) : cache_(std::move(cacheDirectory)) {}

const SrbfMaterialTables::Entry& SrbfMaterialTables::entryFor(const SrbfTableRequest& request,
                                                              Diagnostics& diagnostics) {
    const std::string key = srbfTableKey(request);
    auto found = entries_.find(key);
    if (found != entries_.end()) return found->second;
    Entry entry;
    entry.table = cache_.table(request, diagnostics);
    entry.halfTexels = entry.table->halfTexels();
    entry.uniform = srbfUniformDomeResponse(*entry.table);
    return entries_.emplace(key, std::move(entry)).first->second;
}

SrbfTableUpload SrbfMaterialTables::tablesFor(const std::vector<HairMaterial>& materials, Diagnostics& diagnostics) {
    SrbfTableUpload upload;
    std::vector<const Entry*> marschner, kajiyaKay;
    auto texels = [](const Entry& entry) {
        return gl::SrbfTableTexels{entry.table->width(), entry.table->height(), entry.table->depth(),
                                   &entry.halfTexels};
    };
    bool overflowWarned = false;
    for (const HairMaterial& material : materials) {
        glm::ivec2 tables(0);
        if (material.model == ShadingModel::Marschner) {
            const Entry& entry = entryFor(srbfAbsorbsPerFragment(material)
                                              ? srbfMarschnerLobeTableRequest(material.marschner)
                                              : srbfMarschnerTableRequest(material.marschner),
                                          diagnostics);
            auto at = std::find(marschner.begin(), marschner.end(), &entry);
            if (at == marschner.end() && marschner.size() == kMaxSrbfMarschnerTables) {
                if (!overflowWarned)
                    diagnostics.warn("render", fmt::format("more than {} Marschner materials under a dome: the others "
                                                           "are lit with the first one's SRBF table",
                                                           kMaxSrbfMarschnerTables));
                overflowWarned = true;
                at = marschner.begin();
            } else if (at == marschner.end()) {
                at = marschner.insert(marschner.end(), &entry);
            }
            tables.x = int(at - marschner.begin());
        } else if (material.model == ShadingModel::KajiyaKay) {
            const Entry& entry = entryFor(srbfKajiyaKayTableRequest(material.kajiyaKay.shininess), diagnostics);
            auto at = std::find(kajiyaKay.begin(), kajiyaKay.end(), &entry);
            if (at == kajiyaKay.end()) at = kajiyaKay.insert(kajiyaKay.end(), &entry);
            tables.x = int(at - kajiyaKay.begin());
        }
        upload.materialTables.push_back(tables);
    }
    for (const Entry* entry : marschner) {
        upload.marschner.push_back(texels(*entry));
        upload.uniformRows.push_back(entry->uniform);
    }
    for (const Entry* entry : kajiyaKay) {
        upload.kajiyaKay.push_back(texels(*entry));
        upload.uniformRows.push_back(entry->uniform);
    }
    // Uniform-dome rows: Marschner tables' first, then Kajiya-Kay's.
    for (size_t m = 0; m < materials.size(); ++m) {
        glm::ivec2& tables = upload.materialTables[m];
        if (materials[m].model == ShadingModel::Marschner) tables.y = tables.x;
        else if (materials[m].model == ShadingModel::KajiyaKay) tables.y = int(marschner.size()) + tables.x;
    }
    return upload;
}

}  // namespace hdhair
