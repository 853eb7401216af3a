// The A/B comparison's budget follows the machine (live/ab_budget.h): on a machine too slow for the full
// budget within 20% of the edit, the plan is cut (rounds, then samples, then size) to fit; it never drops
// below the smallest comparison that gives both verdicts, and it learns the machine from what ran.
#include <gtest/gtest.h>

#include "live/ab_budget.h"

using wb::live::ABBudget;
using wb::live::ABBudgetPlanner;

TEST(ABBudget, WithoutAnEditTimeTheFullBudgetRuns) {
  ABBudgetPlanner planner;
  const auto p = planner.plan(ABBudget{}, -1.0, 1);
  EXPECT_FALSE(p.reduced);
  EXPECT_EQ(p.budget.width, 64u);
  EXPECT_EQ(p.budget.spp, 4u);
}

TEST(ABBudget, ASlowMachineGetsACutBudgetThatFitsTheAllowance) {
  ABBudgetPlanner planner;
  planner.setRateHint(2.0);  // pixel samples per ms: a 64x64 render takes ~2 s
  const double editMs = 8000.0;
  const auto p = planner.plan(ABBudget{}, editMs, 1);
  EXPECT_TRUE(p.reduced);
  EXPECT_NEAR(p.allowedMs, ABBudgetPlanner::kMaxCostRatio * editMs, 1e-9);
  EXPECT_FALSE(p.overAllowance) << p.summary();
  EXPECT_LE(p.estimatedMs, p.allowedMs) << p.summary();
  EXPECT_LT(p.budget.width * p.budget.height, 64u * 64u) << p.summary();
  EXPECT_GE(p.budget.spp, ABBudgetPlanner::kMinSpp);
  EXPECT_GE(p.budget.rounds, ABBudgetPlanner::kMinRounds);
  EXPECT_NE(p.summary().find("of this edit"), std::string::npos) << p.summary();
}

TEST(ABBudget, AMachineTooSlowForAnyRunsTheSmallestAndSaysSo) {
  ABBudgetPlanner planner;
  planner.setRateHint(0.001);
  const auto p = planner.plan(ABBudget{}, 100.0, 2);
  EXPECT_TRUE(p.overAllowance);
  EXPECT_EQ(p.budget.spp, ABBudgetPlanner::kMinSpp);
  EXPECT_EQ(p.budget.rounds, ABBudgetPlanner::kMinRounds);
  EXPECT_EQ(std::max(p.budget.width, p.budget.height), ABBudgetPlanner::kMinSize);
  EXPECT_NE(p.summary().find("still over"), std::string::npos) << p.summary();
}

TEST(ABBudget, WhatRanCalibratesTheNextPlan) {
  ABBudgetPlanner planner;
  const ABBudget full{};
  // The first comparison ran with the full budget and took 10 s: the next edit of 5 s gets a smaller plan.
  const auto first = planner.plan(full, -1.0, 1);
  planner.observe(first, 10000.0);
  EXPECT_NEAR(planner.estimateMs(full), 10000.0, 1000.0);
  const auto next = planner.plan(full, 5000.0, 1);
  EXPECT_TRUE(next.reduced);
  EXPECT_LE(next.estimatedMs, next.allowedMs) << next.summary();
}
