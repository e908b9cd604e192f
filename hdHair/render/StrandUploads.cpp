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

    // Drop prims that are no longer drawn: their ranges become holes.
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

    for (size_t i = 0; i < prims.size(); ++i) {
        const DrawnPrim& prim = prims[i];
        const uint64_t count = prim.curves->segmentCount(), controls = prim.curves->controlPoints.size();
        auto found = resident_.find(prim.path);
        if (found != resident_.end() && found->second.curves == prim.curves &&
            found->second.primAndInstance == prim.primAndInstance) {
            Resident& resident = found->second;
            if (resident.material != prim.material) {
                resident.material = prim.material;
                plan.writes.push_back({i, true});
            }
            plan.ranges[i] = resident.range;
            plan.firstControls[i] = resident.firstControl;
            plan.slots[i] = resident.slot;
            continue;
        }
        if (found == resident_.end()) {
            Resident& added = resident_[prim.path];
            if (freeSlots_.empty()) {
                added.slot = slotEnd_++;
            } else {
                added.slot = *freeSlots_.begin();
                freeSlots_.erase(freeSlots_.begin());
            }
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
        plan.ranges[i] = resident.range;
        plan.firstControls[i] = resident.firstControl;
        plan.slots[i] = resident.slot;
        plan.writes.push_back({i, false});
        plan.writtenSegments += count;
    }
    plan.slotCount = slotEnd_;

    for (const auto& [path, resident] : resident_) plan.liveSegments += resident.range.count;
    if (end_ - plan.liveSegments > plan.liveSegments && end_ - plan.liveSegments > kHolesWorthPacking) {
        // Pack every drawn prim again, in draw order.
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
    plan.holeSegments = end_ - plan.liveSegments;
    plan.capacityNeeded = end_;
    plan.controlCapacityNeeded = controlEnd_;

    plan.drawRanges = gl::joinedRanges(plan.ranges);
    return plan;
}

}  // namespace hdhair
