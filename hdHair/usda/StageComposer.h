#pragma once
// Builds a Stage from layers: loads the root layer and every sublayer,
// reference and payload it reaches, then composes prims (see Stage.h and
// README.md for the rules). Internal to hdhair_usda; use Stage::open.

#include <memory>
#include <string>

#include "hdHair/usda/Stage.h"

namespace hdhair::usda {

class StageComposer {
public:
    static std::unique_ptr<Stage> openFile(const std::string& path);
    static std::unique_ptr<Stage> openText(const std::string& text, const std::string& identifier,
                                           const std::string& baseDirectory);
};

}  // namespace hdhair::usda
