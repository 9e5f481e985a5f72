// The stress share's plan (stress_share_plan.hpp).
#include "mpm/stress_share_plan.hpp"
#include <algorithm>
#include <cmath>

namespace burst {

std::vector<ShareTransfer> StressSharePlan(const std::vector<ShareLoad> &loads, bool by_time, PetscReal threshold, PetscInt min_points, bool *used_time)
{
  const PetscMPIInt size = (PetscMPIInt)loads.size();
  for (const ShareLoad &l : loads)
    if (l.count > 0 && !(l.seconds_per_point > 0)) by_time = false;
  if (used_time) *used_time = by_time;
  // a rank's work in seconds (with unit cost per point: in points); the points sent are spread over
  // the sender's array, so a point it sends costs its receiver the sender's time per point
  std::vector<PetscReal> cost(size), work(size);
  PetscReal              total = 0, most = 0;
  PetscMPIInt            busiest = 0;
  for (PetscMPIInt r = 0; r < size; ++r) {
    cost[r] = by_time ? loads[r].seconds_per_point : 1;
    work[r] = loads[r].count * cost[r];
    total += work[r];
    if (work[r] > most) most = work[r], busiest = r;
  }
  std::vector<ShareTransfer> plan;
  const PetscReal            mean = total / size;
  if (!(most > (1 + threshold) * mean && (most - mean) / cost[busiest] >= min_points)) return plan;
  // bisection on the level T
  auto      room = [&](PetscMPIInt r, PetscReal level) { return std::max<PetscReal>(0, level - work[r]) / (by_time ? loads[r].receive_factor : 1); };
  auto      sent = [&](PetscMPIInt r, PetscReal level) { return work[r] > level ? std::min(work[r], (work[r] - level) / (1 - loads[r].overhead)) : 0; };
  PetscReal lo = mean, hi = most;
  for (int it = 0; it < 60; ++it) {
    const PetscReal level = (lo + hi) / 2;
    PetscReal       out = 0, taken = 0;
    for (PetscMPIInt r = 0; r < size; ++r) out += sent(r, level), taken += room(r, level);
    if (out > taken) lo = level;
    else hi = level;
  }
  std::vector<PetscReal> surplus(size); // seconds of the senders' work to send (> 0) or to take (< 0)
  for (PetscMPIInt r = 0; r < size; ++r) surplus[r] = work[r] > hi ? sent(r, hi) : -room(r, hi);
  std::vector<PetscInt64> points_left(size); // a sender's points not yet given away
  for (PetscMPIInt r = 0; r < size; ++r) points_left[r] = (PetscInt64)loads[r].count;
  for (PetscMPIInt s = 0, r = 0; s < size && r < size;) {
    if (surplus[s] <= 0 || points_left[s] <= 0) {
      ++s;
      continue;
    }
    if (surplus[r] >= 0) {
      ++r;
      continue;
    }
    const PetscReal  seconds = std::min(surplus[s], -surplus[r]);
    const PetscInt64 k       = std::min(points_left[s], (PetscInt64)std::llround(seconds / cost[s]));
    if (k > 0) {
      plan.push_back({s, r, k});
      points_left[s] -= k;
    }
    surplus[s] -= seconds;
    surplus[r] += seconds;
  }
  return plan;
}

} // namespace burst
