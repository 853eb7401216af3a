// The A/B comparison's budget as the machine allows it: a comparison costs at most kMaxCostRatio of the edit
// it compares, by construction. Before each comparison the planner estimates what the full budget would cost
// on this machine (a model of the stand-in's renders: a fixed cost per render plus a cost per pixel,
// calibrated by every comparison that ran) and, when that is over the allowance, takes fewer timing rounds,
// then fewer samples, then a smaller image, down to the smallest comparison that still gives both verdicts.
// It never switches the comparison off: on a machine too slow even for that, the smallest comparison runs and
// says so.
#pragma once
#include <cstdint>
#include <string>

#include "live/ab_comparison.h"

namespace wb::live {

// What one planned comparison is: the budget it runs with, the full budget it was cut from, the allowance
// and the estimate, and a line for the panel saying so.
struct ABPlan {
  ABBudget budget;
  ABBudget full;
  uint32_t comparisons = 1;     // rebuilt pipelines compared (they share the allowance)
  double allowedMs = -1;        // kMaxCostRatio of the edit's time (-1: no edit time known, the full budget)
  double estimatedMs = -1;      // the model's estimate of the comparisons with `budget`
  bool reduced = false;         // smaller than the full budget
  bool overAllowance = false;   // even the smallest comparison is estimated over the allowance
  std::string summary() const;  // "64x64, 4 spp, 5 rounds" or what was cut and why
};

class ABBudgetPlanner {
 public:
  static constexpr double kMaxCostRatio = 0.2;
  // The smallest comparison that still gives both verdicts: two runs per side for the paired noise, two
  // alternating timing rounds, 16x16 pixels.
  static constexpr uint32_t kMinSpp = 2, kMinRounds = 2, kMinSize = 16;

  // Renders of one comparison with `b`: each of spp runs renders both sides, each round times both sides.
  static uint32_t renders(const ABBudget& b) { return 2 * b.spp + 2 * b.rounds; }

  // A first guess of the device's rate (pixel samples per ms of the live renderer) until a comparison has run
  // on this machine; <= 0 keeps the last one.
  void setRateHint(double pixelsPerMs);
  // The budget for `comparisons` pipelines after an edit that took `editMs` to reach the screen (<= 0: none
  // known, the full budget).
  ABPlan plan(const ABBudget& full, double editMs, uint32_t comparisons) const;
  // A comparison that ran with `plan` took `ms` in all: the model learns this machine's cost.
  void observe(const ABPlan& plan, double ms);
  // The model's estimate of one comparison with `b`.
  double estimateMs(const ABBudget& b) const;

 private:
  double fixedMs_ = 2.0;        // per render: recording, submission, waiting, readback
  double pixelsPerMs_ = 250.0;  // the stand-in's trace rate
  bool calibrated_ = false;     // a comparison ran (the rate hint no longer applies)
};

}  // namespace wb::live
