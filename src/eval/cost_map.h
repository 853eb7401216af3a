// The path tracer's cost AOV made sense of on the host: what a sample costs per pixel (the shader clock's
// units), how that splits between trace calls and shading, each pixel's share of the frame, and the
// inefficiency map: relative variance x cost, the pixels that are both noisy and expensive (a Monte Carlo
// estimator's efficiency is 1 / (variance x time)). The window's `cost` and `inefficiency` views, `render
// --aov cost` and `bench` read it. The images come from render::PathTracer (Aov::Cost, Aov::Stats, the
// accumulation).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace wb::eval {

// Which per-pixel value stands for a pixel's cost: the mean clocks of its samples, or their running median
// (vk::DevicePolicy::costByMedian).
enum class CostEstimate { Mean, Median };
const char* costEstimateName(CostEstimate e);  // "mean" | "median"

struct CostSummary {
  uint32_t clock = 0;  // WB_CLOCK_* (shaders/shared/pathtracer_types.h): 0, no shader clock: every cost is 0
  CostEstimate estimate = CostEstimate::Mean;
  uint32_t width = 0, height = 0;
  // A pixel's clocks per sample (`estimate`) over the pixels: mean, median, 95th and 99th percentiles, the
  // most expensive pixel. The views' full scale is the 95th.
  double mean = 0, p50 = 0, p95 = 0, p99 = 0, max = 0;
  double frame = 0;  // the sum over pixels: one sample of the whole image (each pixel's share is its / frame)
  // Shares of the frame's clocks: trace calls (traversal, any-hit), shading (closest-hit, environment miss),
  // the rest (raygen: the path loop, sampling, accumulation).
  double traceShare = 0, shadeShare = 0, raygenShare = 0;
  // Inefficiency (relative variance of one sample x its clocks): the mean, 95th and 99th percentiles over
  // pixels with a non-zero mean, for normalising the view.
  double inefficiencyMean = 0, inefficiencyP95 = 0, inefficiencyP99 = 0;
  // The cost variant traced each subgroup's lanes alone (vk::DevicePolicy::costIsolatesLanes): a pixel's
  // clocks are its own path's, not its subgroup's slowest lane's. Set by the caller, which knows the tracer.
  bool lanesIsolated = false;
  bool valid() const { return clock != 0 && frame > 0; }
};

// The clock's units for a legend: "cycles" (the subgroup clock), "device ticks", or "" without a clock.
std::string clockUnits(uint32_t clock);

// Each pixel's cost from the cost AOV (RGBA: r the mean, a the running median).
std::vector<double> pixelCosts(const std::vector<float>& cost, uint32_t width, uint32_t height,
                               CostEstimate e);

// Per pixel: relative variance of one sample (from the accumulation's mean and the stats AOV's mean
// luminance^2) times the pixel's cost; 0 where the mean is 0. `accum`, `stats` and `cost` are RGBA float
// images of width x height.
std::vector<double> inefficiencyMap(const std::vector<float>& accum, const std::vector<float>& stats,
                                    const std::vector<float>& cost, uint32_t width, uint32_t height,
                                    CostEstimate e);

CostSummary summarizeCost(const std::vector<float>& accum, const std::vector<float>& stats,
                          const std::vector<float>& cost, uint32_t width, uint32_t height, uint32_t clock,
                          CostEstimate e);

// `values` (one per pixel) as an RGBA8 heat map (shaders/shared/heat_ramp.h) with `full` at the top of the
// ramp, for writePng8.
std::vector<uint8_t> heatMapRgba8(const std::vector<double>& values, double full);

}  // namespace wb::eval
