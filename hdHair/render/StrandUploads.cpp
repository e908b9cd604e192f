#include "hdHair/render/StrandUploads.h"

#include <set>

namespace hdhair {

namespace {

// Holes are packed away once they are more than the live segments and more
// than this many segments (64 K segments are 1-8 MB of control points): below
// that, a full upload costs more than the memory it would save.
constexpr uint64_t kHolesWorthPacking = 65536;

}  // namespace

void StrandUploads::reset() {
    resident_.clear();
    end_ = 0;
    controlEnd_ = 0;
    freeSlots_.clear();
    slotEnd_ = 0;
}

StrandUploadPlan StrandUploads::update(const std::vector<DrawnPrim>& prims) {
    StrandUploadPlan plan;
    plan.ranges.resize(prims.size());
    plan.firstControls.resize(prims.size());
    plan.slots.resize(prims.size());

    dropUndrawnPrims(prims);
    for (size_t i = 0; i < prims.size(); ++i) placePrim(i, prims[i], plan);
    plan.slotCount = slotEnd_;

    for (const auto& [path, resident] : resident_) plan.liveSegments += resident.range.count;
    if (end_ - plan.liveSegments > plan.liveSegments && end_ - plan.liveSegments > kHolesWorthPacking)
        repack(prims, plan);
    plan.holeSegments = end_ - plan.liveSegments;
    plan.capacityNeeded = end_;
    plan.controlCapacityNeeded = controlEnd_;

    plan.drawRanges = gl::joinedRanges(plan.ranges);
    return plan;
}

// Drop prims that are no longer drawn: their ranges become holes.
void StrandUploads::dropUndrawnPrims(const std::vector<DrawnPrim>& prims) {
    std::set<std::string> drawn;
    for (const DrawnPrim& prim : prims) drawn.insert(prim.path);
    for (auto it = resident_.begin(); it != resident_.end();) {
        if (drawn.count(it->first)) {
            ++it;
            continue;
        }
        freeSlots_.insert(it->second.slot);
        it = resident_.erase(it);
    }
}

// Drawn prim `index`'s range, control points and slot: those it has when its
// curves and ids are already on the GPU, or else new ones at the end when it
// is new or resized, and the write that sends it.
void StrandUploads::placePrim(size_t index, const DrawnPrim& prim, StrandUploadPlan& plan) {
    const uint64_t count = prim.curves->segmentCount(), controls = prim.curves->controlPoints.size();
    auto found = resident_.find(prim.path);
    if (found != resident_.end() && found->second.curves == prim.curves &&
        found->second.primAndInstance == prim.primAndInstance) {
        Resident& resident = found->second;
        if (resident.material != prim.material) {
            resident.material = prim.material;
            plan.writes.push_back({index, true});
        }
        plan.ranges[index] = resident.range;
        plan.firstControls[index] = resident.firstControl;
        plan.slots[index] = resident.slot;
        return;
    }
    if (found == resident_.end()) {
        Resident& added = resident_[prim.path];
        added.slot = takeSlot();
    }
    Resident& resident = resident_[prim.path];
    if (found == resident_.end() || resident.range.count != count || resident.controlCount != controls) {
        resident.range = gl::SegmentRange{end_, count};  // new ranges at the end
        end_ += count;
        resident.firstControl = controlEnd_;
        resident.controlCount = controls;
        controlEnd_ += controls;
    }
    resident.curves = prim.curves;
    resident.primAndInstance = prim.primAndInstance;
    resident.material = prim.material;
    plan.ranges[index] = resident.range;
    plan.firstControls[index] = resident.firstControl;
    plan.slots[index] = resident.slot;
    plan.writes.push_back({index, false});
    plan.writtenSegments += count;
}

// The lowest freed slot, or a new one past the end.
uint32_t StrandUploads::takeSlot() {
    if (freeSlots_.empty()) return slotEnd_++;
    const uint32_t slot = *freeSlots_.begin();
    freeSlots_.erase(freeSlots_.begin());
    return slot;
}

// Pack every drawn prim again, in draw order.
void StrandUploads::repack(const std::vector<DrawnPrim>& prims, StrandUploadPlan& plan) {
    end_ = 0;
    controlEnd_ = 0;
    plan.writes.clear();
    plan.writtenSegments = 0;
    for (size_t i = 0; i < prims.size(); ++i) {
        Resident& resident = resident_.at(prims[i].path);
        resident.range = gl::SegmentRange{end_, resident.range.count};
        end_ += resident.range.count;
        resident.firstControl = controlEnd_;
        controlEnd_ += resident.controlCount;
        plan.ranges[i] = resident.range;
        plan.firstControls[i] = resident.firstControl;
        plan.writes.push_back({i, false});
        plan.writtenSegments += resident.range.count;
    }
    plan.repacked = true;
}

}  // namespace hdhair
