#pragma once
// Which GPU segments and control points each drawn prim owns
// (gl::StrandGeometry: the two are allocated side by side), its slot in the
// drawn prims' table (ids and material, rewritten every frame: a few bytes a
// prim), and what a frame must send: a prim whose prepared curves and ids are
// those already on the GPU sends nothing, one whose material index alone
// changed only changes its table entry, a changed prim of the same size
// rewrites its own range, and a new or resized prim takes a range at the end. Ranges freed by removed or
// resized prims stay as holes until they outweigh the live segments; then
// every prim is packed again in draw order (one full upload).
//
// Pure bookkeeping, no GL: the upload pass carries out the writes.

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/gl/SegmentRange.h"

namespace hdhair {

struct DrawnPrim {
    std::string path;  // engine prim path (an instance has its own)
    std::shared_ptr<const PreparedCurves> curves;
    glm::ivec2 primAndInstance{-1, 0};
    int32_t material = 0;
};

struct StrandWrite {
    size_t prim = 0;            // index into the frame's drawn prims
    bool materialOnly = false;  // the segments are there; only their material (table entry) changed
};

struct StrandUploadPlan {
    std::vector<gl::SegmentRange> ranges;      // per drawn prim, in the same order
    std::vector<uint64_t> firstControls;       // per drawn prim: where its control points start
    std::vector<uint32_t> slots;               // per drawn prim: its entry in the drawn prims' table
    uint32_t slotCount = 0;                    // the table's size (freed slots are reused)
    std::vector<StrandWrite> writes;      // what to send this frame
    uint64_t capacityNeeded = 0;          // segments the GPU buffers must hold
    uint64_t controlCapacityNeeded = 0;   // and control points
    uint64_t writtenSegments = 0;         // geometry sent (material-only writes not counted)
    uint64_t liveSegments = 0, holeSegments = 0;
    bool repacked = false;
    // The ranges to draw when order does not matter: drawn prims' ranges in
    // draw order, adjacent ones merged.
    std::vector<gl::SegmentRange> drawRanges;
};

class StrandUploads {
public:
    StrandUploadPlan update(const std::vector<DrawnPrim>& prims);
    // Forgets everything (the GPU buffers were recreated).
    void reset();

private:
    struct Resident {
        std::shared_ptr<const PreparedCurves> curves;
        glm::ivec2 primAndInstance{-1, 0};
        int32_t material = 0;
        gl::SegmentRange range;
        uint64_t firstControl = 0, controlCount = 0;
        uint32_t slot = 0;
    };
    void dropUndrawnPrims(const std::vector<DrawnPrim>& prims);
    void placePrim(size_t index, const DrawnPrim& prim, StrandUploadPlan& plan);
    uint32_t takeSlot();
    void repack(const std::vector<DrawnPrim>& prims, StrandUploadPlan& plan);

    std::map<std::string, Resident> resident_;
    uint64_t end_ = 0;         // one past the last allocated segment
    uint64_t controlEnd_ = 0;  // and control point
    std::set<uint32_t> freeSlots_;
    uint32_t slotEnd_ = 0;  // one past the highest slot handed out
};

}  // namespace hdhair
