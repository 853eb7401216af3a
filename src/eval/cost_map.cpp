#include "eval/cost_map.h"

#include <algorithm>
#include <cmath>

#include "shared/heat_ramp.h"
#include "shared/pathtracer_types.h"

namespace wb::eval {
namespace {

double luminance(const float* rgb) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// The p-quantile of an ascending series by the nearest rank (common/statistics.h's, without its copy).
double sortedPercentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  return sorted[std::min(sorted.size() - 1, size_t(p * double(sorted.size() - 1) + 0.5))];
}

}  // namespace

std::string clockUnits(uint32_t clock) {
  return clock == WB_CLOCK_SUBGROUP ? "cycles" : clock == WB_CLOCK_DEVICE ? "device ticks" : "";
}

const char* costEstimateName(CostEstimate e) {
  return e == CostEstimate::Median ? "median" : "mean";
}

std::vector<double> pixelCosts(const std::vector<float>& cost, uint32_t width, uint32_t height,
                               CostEstimate e) {
  const size_t n = size_t(width) * height;
  std::vector<double> out(n, 0.0);
  if (cost.size() < 4 * n) return out;
  const size_t channel = e == CostEstimate::Median ? 3 : 0;
  for (size_t i = 0; i < n; ++i) out[i] = cost[4 * i + channel];
  return out;
}

std::vector<double> inefficiencyMap(const std::vector<float>& accum, const std::vector<float>& stats,
                                    const std::vector<float>& cost, uint32_t width, uint32_t height,
                                    CostEstimate e) {
  const size_t n = size_t(width) * height;
  std::vector<double> out = pixelCosts(cost, width, height, e);
  const bool images = accum.size() >= 4 * n && stats.size() >= 4 * n;
  for (size_t i = 0; i < n; ++i) {
    const double mean = images ? luminance(&accum[4 * i]) : 0.0;
    const double variance = images ? std::max(double(stats[4 * i]) - mean * mean, 0.0) : 0.0;
    out[i] = mean > 0.0 && std::isfinite(mean) ? out[i] * variance / (mean * mean) : 0.0;
  }
  return out;
}

CostSummary summarizeCost(const std::vector<float>& accum, const std::vector<float>& stats,
                          const std::vector<float>& cost, uint32_t width, uint32_t height, uint32_t clock,
                          CostEstimate e) {
  CostSummary s;
  s.clock = clock;
  s.estimate = e;
  s.width = width;
  s.height = height;
  const size_t n = size_t(width) * height;
  if (cost.size() < 4 * n || n == 0) return s;
  std::vector<double> perPixel = pixelCosts(cost, width, height, e);
  double total = 0, trace = 0, shade = 0;  // the means' sums: the split of the time
  for (size_t i = 0; i < n; ++i) {
    s.frame += perPixel[i];
    s.max = std::max(s.max, perPixel[i]);
    total += cost[4 * i];
    trace += cost[4 * i + 1];
    shade += cost[4 * i + 2];
  }
  s.mean = s.frame / double(n);
  std::sort(perPixel.begin(), perPixel.end());
  s.p50 = sortedPercentile(perPixel, 0.5);
  s.p95 = sortedPercentile(perPixel, 0.95);
  s.p99 = sortedPercentile(perPixel, 0.99);
  if (total > 0) {
    s.traceShare = trace / total;
    s.shadeShare = shade / total;
    s.raygenShare = std::max(0.0, 1.0 - s.traceShare - s.shadeShare);
  }
  std::vector<double> ineff;
  for (double v : inefficiencyMap(accum, stats, cost, width, height, e))
    if (v > 0) ineff.push_back(v);
  if (!ineff.empty()) {
    double sum = 0;
    for (double v : ineff) sum += v;
    s.inefficiencyMean = sum / double(ineff.size());
    std::sort(ineff.begin(), ineff.end());
    s.inefficiencyP95 = sortedPercentile(ineff, 0.95);
    s.inefficiencyP99 = sortedPercentile(ineff, 0.99);
  }
  return s;
}

std::vector<uint8_t> heatMapRgba8(const std::vector<double>& values, double full) {
  std::vector<uint8_t> out(values.size() * 4);
  for (size_t i = 0; i < values.size(); ++i) {
    const float t = full > 0 ? float(values[i] / full) : 0.0f;
    const glm::vec3 c = gpu::heatRamp(std::isfinite(t) ? t : 1.0f);
    for (int k = 0; k < 3; ++k) out[4 * i + k] = uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
    out[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace wb::eval
