#include "live/ab_budget.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace wb::live {

std::string ABPlan::summary() const {
  char buf[320];
  if (!reduced) {
    std::snprintf(buf, sizeof buf, "%ux%u, %u spp, %u rounds", budget.width, budget.height, budget.spp,
                  budget.rounds);
    return buf;
  }
  std::snprintf(buf, sizeof buf,
                "%ux%u, %u spp, %u rounds (of %ux%u, %u, %u): %s%.0f%% of this edit's %.0f ms on this "
                "machine, est. %.0f ms",
                budget.width, budget.height, budget.spp, budget.rounds, full.width, full.height, full.spp,
                full.rounds, overAllowance ? "the smallest comparison, still over " : "fits ",
                ABBudgetPlanner::kMaxCostRatio * 100.0, allowedMs / ABBudgetPlanner::kMaxCostRatio,
                estimatedMs);
  return buf;
}

void ABBudgetPlanner::setRateHint(double pixelsPerMs) {
  if (!calibrated_ && pixelsPerMs > 0) pixelsPerMs_ = pixelsPerMs;
}

double ABBudgetPlanner::estimateMs(const ABBudget& b) const {
  const double pixels = double(std::max(1u, b.width)) * double(std::max(1u, b.height));
  return double(renders(b)) * (fixedMs_ + pixels / std::max(pixelsPerMs_, 1e-3));
}

ABPlan ABBudgetPlanner::plan(const ABBudget& full, double editMs, uint32_t comparisons) const {
  ABPlan p;
  p.full = p.budget = full;
  p.comparisons = std::max(1u, comparisons);
  auto total = [&](const ABBudget& b) { return estimateMs(b) * double(p.comparisons); };
  p.estimatedMs = total(full);
  if (editMs <= 0) return p;
  p.allowedMs = kMaxCostRatio * editMs;
  if (p.estimatedMs <= p.allowedMs) return p;

  // The ladder, cheapest loss first: timing rounds (the speed verdict keeps its alternation), samples (the
  // image verdict keeps its paired noise), then the image's size, then the last rounds.
  std::vector<ABBudget> ladder;
  ABBudget b = full;
  auto step = [&](auto change) {
    change(b);
    ladder.push_back(b);
  };
  if (b.rounds > 3) step([](ABBudget& x) { x.rounds = 3; });
  if (b.spp > kMinSpp) step([](ABBudget& x) { x.spp = kMinSpp; });
  for (uint32_t size : {48u, 32u, 24u, kMinSize}) {
    if (std::max(b.width, b.height) <= size) continue;
    step([&](ABBudget& x) {
      // The longer side to `size`, the aspect kept.
      const double scale = double(size) / double(std::max(x.width, x.height));
      x.width = std::max(1u, uint32_t(double(x.width) * scale + 0.5));
      x.height = std::max(1u, uint32_t(double(x.height) * scale + 0.5));
    });
  }
  if (b.rounds > kMinRounds) step([](ABBudget& x) { x.rounds = kMinRounds; });
  p.reduced = !ladder.empty();
  for (const ABBudget& candidate : ladder) {
    p.budget = candidate;
    p.estimatedMs = total(candidate);
    if (p.estimatedMs <= p.allowedMs) return p;
  }
  p.overAllowance = true;
  return p;
}

void ABBudgetPlanner::observe(const ABPlan& plan, double ms) {
  if (ms <= 0) return;
  // One observation cannot separate the fixed cost from the per-pixel one: the fixed cost is kept and the
  // rate is what makes the model match the observation (the next plan's sizes are near this one's).
  const double perRender = ms / double(plan.comparisons) / double(renders(plan.budget));
  const double pixels = double(std::max(1u, plan.budget.width)) * double(std::max(1u, plan.budget.height));
  const double traceMs = std::max(perRender - fixedMs_, 0.05 * perRender);
  fixedMs_ = std::min(fixedMs_, perRender);
  const double measured = pixels / traceMs;
  pixelsPerMs_ = calibrated_ ? 0.5 * pixelsPerMs_ + 0.5 * measured : measured;
  calibrated_ = true;
}

}  // namespace wb::live
