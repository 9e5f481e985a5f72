// The stress share's plan (src/mpm/stress_share_plan.hpp) against plans worked out by hand.
#include "mpm/stress_share_plan.hpp"
#include <gtest/gtest.h>

using namespace burst;

namespace {

constexpr PetscInt kMin = 256; // -mpm_stress_share_min's default

void ExpectPlan(const std::vector<ShareTransfer> &plan, const std::vector<ShareTransfer> &expected)
{
  ASSERT_EQ(plan.size(), expected.size());
  for (size_t t = 0; t < plan.size(); ++t) {
    EXPECT_EQ(plan[t].sender, expected[t].sender) << "transfer " << t;
    EXPECT_EQ(plan[t].receiver, expected[t].receiver) << "transfer " << t;
    EXPECT_EQ(plan[t].count, expected[t].count) << "transfer " << t;
  }
}

} // namespace

TEST(StressSharePlan, CountsTwoRanks)
{
  // 1000 points against none, overhead 0.3: the sender of s points is busy 1000 - 0.7 s, the
  // receiver s; equal at s = 1000/1.7 = 588.235: 588 points
  ExpectPlan(StressSharePlan({{1000, 0.3, 0, 1}, {0, 0.3, 0, 1}}, false, 0.1, kMin), {{0, 1, 588}});
}

TEST(StressSharePlan, TimeTwoRanks)
{
  // 10,000 points each, 2 and 1 us per point: work 20 and 10 ms. Sender overhead 0.2, receiver
  // factor 1.5: 20 - 0.8 s = 10 + 1.5 s at s = 10/2.3 = 4.3478 ms of the sender's work, i.e.
  // 4.3478e-3/2e-6 = 2173.9: 2174 points
  bool used_time = false;
  ExpectPlan(StressSharePlan({{10000, 0.2, 2e-6, 1}, {10000, 0.3, 1e-6, 1.5}}, true, 0.1, kMin, &used_time), {{0, 1, 2174}});
  EXPECT_TRUE(used_time);
  // the same loads planned by count: even, nothing to share
  ExpectPlan(StressSharePlan({{10000, 0.2, 2e-6, 1}, {10000, 0.3, 1e-6, 1.5}}, false, 0.1, kMin, &used_time), {});
  EXPECT_FALSE(used_time);
}

TEST(StressSharePlan, TimeNeedsEveryRankMeasured)
{
  // a rank holding points has not measured its time yet: the plan falls back to counts
  // (1300 against 700, overhead 0: 1300 - s = 700 + s at s = 300)
  bool used_time = true;
  ExpectPlan(StressSharePlan({{1300, 0, 2e-6, 1}, {700, 0, 0, 1}}, true, 0.1, kMin, &used_time), {{0, 1, 300}});
  EXPECT_FALSE(used_time);
  // a rank without points need not have measured: the work is in seconds (rank 1's is 0);
  // 1300 points at 1 us, overhead 0, factor 1: s = 650 us = 650 points
  ExpectPlan(StressSharePlan({{1300, 0, 1e-6, 1}, {0, 0, 0, 1}}, true, 0.1, kMin, &used_time), {{0, 1, 650}});
  EXPECT_TRUE(used_time);
}

TEST(StressSharePlan, ThresholdAndMinimum)
{
  // 1050 against 950: the busiest is 1.05 x the mean, under 1 + 0.1
  ExpectPlan(StressSharePlan({{1050, 0, 0, 1}, {950, 0, 0, 1}}, false, 0.1, kMin), {});
  // threshold 0.01 lets it share (50 points each way to even out), but 50 < min_points 256
  ExpectPlan(StressSharePlan({{1050, 0, 0, 1}, {950, 0, 0, 1}}, false, 0.01, kMin), {});
  // and with min_points 50 it shares exactly those 50
  ExpectPlan(StressSharePlan({{1050, 0, 0, 1}, {950, 0, 0, 1}}, false, 0.01, 50), {{0, 1, 50}});
}

TEST(StressSharePlan, ThreeRanksInRankOrder)
{
  // 3000, 0, 0 points, overhead 0: the level T = 1000, a thousand points to each receiver in order
  ExpectPlan(StressSharePlan({{3000, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}}, false, 0.1, kMin), {{0, 1, 1000}, {0, 2, 1000}});
  // two senders and one receiver: 2000, 2000, 0 at overhead 0: T = 4000/3 = 1333.3; each sender
  // gives 666.67 (667 points, rounded), rank 0 first
  ExpectPlan(StressSharePlan({{2000, 0, 0, 1}, {2000, 0, 0, 1}, {0, 0, 0, 1}}, false, 0.1, kMin), {{0, 2, 667}, {1, 2, 667}});
}

TEST(StressSharePlan, SenderGivesAtMostItsPoints)
{
  // a receiver ten times as fast on the sender's points (factor 0.1), overhead 0.9: uncapped, the
  // sender would send (1000 - T)/0.1 and the receiver take 10 T, equal at T = 500 with 5000 s of
  // work sent; capped at its 1000 points' worth, the level is T = 100 and all 1000 points go
  ExpectPlan(StressSharePlan({{1000, 0.9, 1e-6, 1}, {0, 0.3, 0, 0.1}}, true, 0.1, kMin), {{0, 1, 1000}});
}
