// The plan of the stress share (src/mpm/stress_share.cxx): which rank sends the update of how many
// of its points to which. A pure function of every rank's load, so that every rank draws the same
// plan and the unit tests check it by hand (tests/unit/test_stress_share_plan.cxx).
#pragma once
#include <petscsys.h>
#include <vector>

namespace burst {

// What a rank tells the others before the plan.
struct ShareLoad {
  PetscReal count;             // its particles
  PetscReal overhead;          // its cost of sending a point (packing, unpacking), as a fraction of updating it, < 1
  PetscReal seconds_per_point; // its measured update time per point of its own (0: not measured yet)
  PetscReal receive_factor;    // a received point's time on it over its sender's time per point, > 0
};

struct ShareTransfer {
  PetscMPIInt sender, receiver;
  PetscInt64  count; // points
};

// The transfers that even out the ranks' work. With by_time, a rank's work is count x
// seconds_per_point (counts alone if a rank holding points has not measured its time yet); else
// its count. Nothing is shared unless the busiest rank's work exceeds (1 + threshold) x the mean by
// at least min_points of its points. The level T at which every rank is busy as long: a sender of s
// of its work is busy for work - (1 - overhead) s = T, a receiver of s for work + receive_factor s
// = T (by_time; 1 with counts), a sender giving away at most its points; senders above T send to
// receivers below it in rank order. *used_time (if given): whether the work was counted in seconds.
std::vector<ShareTransfer> StressSharePlan(const std::vector<ShareLoad> &loads, bool by_time, PetscReal threshold, PetscInt min_points, bool *used_time = nullptr);

} // namespace burst
