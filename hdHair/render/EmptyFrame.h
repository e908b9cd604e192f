#pragma once
// A frame that shows nothing is worth a word when the input is the likely
// reason: a render farm should not accept a blank frame in silence. An empty
// stage without warnings renders its background quietly, as it should.

#include <cstddef>
#include <string>

namespace hdhair {

class Scene;
struct RenderResult;

// "" when `result` covers a pixel (alpha > 0) or the stage has no curves or
// meshes and reading it raised no warning (`warnings`: the count so far);
// otherwise a warning starting "nothing drawn: " that says what the frame
// had and why none of it shows.
std::string whyNothingDrawn(const Scene& scene, const RenderResult& result, size_t warnings);

}  // namespace hdhair
