// What the live session measures and checks beside the image: the GPU time of each pass of every finished
// frame (vk::GpuTimer; the denoiser's as the window's Presenter times it), the path tracer's cost variant
// while a cost view (`cost`, `inefficiency`) is shown with the summary its legend reads (about once a
// second), and the asserts variant while the asserts toggle is on, with their failures. LiveSession drives it
// at frame boundaries.
#pragma once
#include <chrono>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eval/cost_map.h"
#include "live/session_state.h"
#include "render/render_session.h"

namespace wb::live {

// Whether a debug view needs the cost variant.
bool isCostView(uint32_t view);

class Instruments {
 public:
  using Clock = std::chrono::steady_clock;
  // At a frame boundary: switches the path tracer to the variants `state` asks for. True when its program
  // changed (its accumulation restarted).
  bool apply(render::PathTracer& tracer, const SessionState& state);
  // When a submission of `renderer` finished: its passes' GPU times (a trace-only submission's too).
  void submissionFinished(render::Renderer& renderer);
  // When a frame finished (nothing in flight): the cost summary when due, the asserts' failures.
  void frameFinished(render::RenderSession& session, bool pathTracerShown);
  // The denoiser ran in the frame that finished, for `ms` of GPU time (the window's Presenter times it apart
  // from the trace): call before that frame's submissionFinished().
  void denoiseTimed(double ms);

  const std::vector<vk::PassTime>& passTimes() const { return passTimes_; }
  // The denoiser's GPU ms at its last run, while the path tracer denoises (it runs only as samples arrive, so
  // seldom in the frame shown); nullopt before its first run and while it is off.
  std::optional<double> denoiseMs() const { return denoiseOn_ ? denoiseMs_ : std::nullopt; }
  uint64_t passTimesSerial() const { return passTimesSerial_; }  // bumped by every submission timed
  // The GPU milliseconds of the last kHistory timed submissions, all passes summed, oldest first (the
  // panel's GPU time graph).
  static constexpr size_t kHistory = 240;
  const std::deque<float>& passHistory() const { return passHistory_; }
  const std::optional<eval::CostSummary>& cost() const { return cost_; }
  bool costOn() const { return costOn_; }
  const render::AssertReport& asserts() const { return asserts_; }
  const std::map<uint32_t, std::string>& labels() const { return labels_; }

 private:
  bool costOn_ = false, assertsOn_ = false, denoiseOn_ = false;
  std::vector<vk::PassTime> passTimes_;
  std::optional<double> denoiseMs_;
  bool denoiseInRound_ = false;  // the denoiser ran in the submission not yet collected
  uint64_t passTimesSerial_ = 0;
  std::deque<float> passHistory_;
  std::optional<eval::CostSummary> cost_;
  Clock::time_point lastCostRead_{}, lastLabelsRead_{};
  render::AssertReport asserts_;
  std::map<uint32_t, std::string> labels_;
};

}  // namespace wb::live
