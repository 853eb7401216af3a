#include "live/instruments.h"

#include "display/display_types.h"

namespace wb::live {
namespace {

// The cost summary is read back (three images) at most this often.
constexpr double kCostReadSeconds = 1.0;

}  // namespace

bool isCostView(uint32_t view) {
  return view == WB_VIEW_COST || view == WB_VIEW_INEFFICIENCY;
}

bool Instruments::apply(render::PathTracer& tracer, const SessionState& state) {
  render::Instrumentation want;
  want.cost = state.params.mode == render::RenderMode::PathTrace && isCostView(state.params.display.view);
  want.asserts = state.asserts;
  costOn_ = want.cost;
  denoiseOn_ = state.params.mode == render::RenderMode::PathTrace && tracer.settings().denoise;
  assertsOn_ = want.asserts;
  if (!costOn_) cost_.reset();
  if (!assertsOn_) asserts_ = {};
  if (want == tracer.instrumentation()) return false;
  tracer.setInstrumentation(want);
  cost_.reset();
  lastCostRead_ = lastLabelsRead_ = {};
  return true;
}

void Instruments::submissionFinished(render::Renderer& renderer) {
  vk::GpuTimer* timer = renderer.passTimer();
  if (!timer) return;
  const auto& round = timer->collect();
  if (round.empty()) return;  // a submission that recorded no pass keeps the last times
  passTimes_ = round;
  ++passTimesSerial_;
  float total = denoiseInRound_ ? float(*denoiseMs_) : 0.0f;
  denoiseInRound_ = false;
  for (const auto& t : passTimes_) total += float(t.ms);
  passHistory_.push_back(total);
  if (passHistory_.size() > kHistory) passHistory_.pop_front();
}

void Instruments::denoiseTimed(double ms) {
  denoiseMs_ = ms;
  denoiseInRound_ = true;
}

void Instruments::frameFinished(render::RenderSession& session, bool pathTracerShown) {
  auto& tracer = session.pathTracer();
  const auto now = Clock::now();
  if (assertsOn_) asserts_ = tracer.readAsserts();
  // The labels of prints and asserts, from the sources of the installed pipeline (an edit may add some).
  if ((assertsOn_ || tracer.inspection()) &&
      std::chrono::duration<double>(now - lastLabelsRead_).count() >= kCostReadSeconds) {
    labels_ = tracer.debugLabels();
    lastLabelsRead_ = now;
  }
  if (!costOn_ || !pathTracerShown || tracer.samplesAccumulated() == 0) return;
  if (cost_ && std::chrono::duration<double>(now - lastCostRead_).count() < kCostReadSeconds) return;
  lastCostRead_ = now;
  cost_ = tracer.summarizeCost(tracer.readAov(render::Aov::Cost));
}

}  // namespace wb::live
