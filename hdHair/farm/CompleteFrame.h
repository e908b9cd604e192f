#pragma once
// Whether a frame's image is already complete, so a resubmitted job skips it.
// hdhair-record writes images atomically (a temporary sibling renamed over
// the name), so a file under the frame's name is whole unless something else
// wrote it; it is complete when it opens, every pixel decodes and its size is
// the size this job renders (a frame left from another width is rendered again).

#include <string>

namespace hdhair::farm {

// "" when complete, else why not: "missing", "800x600, not 1280x960", "cannot
// read image ...: ...".
std::string whyFrameIncomplete(const std::string& path, int width, int height);

}  // namespace hdhair::farm
