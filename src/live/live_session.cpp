#include "live/live_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene/features.h"

namespace wb::live {

LiveSession::LiveSession(Options o) : state_(std::move(o.state)) {
  state_.params.render.aov = true;  // the debug views read the AOV images
  o.session.settings = state_.params.render;
  o.session.settings.width = o.session.settings.height = 64;  // resized to the view with the first frames
  o.session.hybrid = state_.params.hybrid;
  o.session.mode = render::RenderMode::PathTrace;  // the state's mode is made below
  session_ = std::make_unique<render::RenderSession>(o.session);
  EditLoopOptions lo;
  lo.watchDirs = o.watchDirs;
  lo.ab = ab_.enabled;
  lo.adaptiveBudget = true;  // a comparison costs at most ABBudgetPlanner::kMaxCostRatio of its edit
  loop_ = std::make_unique<EditLoop>(*session_, lo);  // every renderer, the modes made later too
  progressive_ = std::make_unique<render::ProgressiveTracer>(session_->context(), session_->pathTracer());
  state_.materials = session_->scene().materials;
  state_.lights = session_->scene().lights;
  camera_ = session_->sceneCamera();
  applied_ = state_;
  applyMode(true);  // the mode the session opens in is there from the first frame
}

LiveSession::~LiveSession() {
  if (loop_) loop_->hot().stop();
  if (session_) session_->context().waitIdle();
  progressive_.reset();
  ab_.installed.clear();  // the old pipelines kept for Revert
  loop_.reset();          // its passes are the session's renderers'
  session_.reset();
}

void LiveSession::start(std::function<void()> onReady) {
  loop_->start(std::move(onReady));
}

void LiveSession::set(const std::string& name, const std::string& value) {
  applySetting(state_, name, value);
  apply();  // what the caller does next sees the new state
  if (state_.params.mode != session_->mode()) apply(true);
}

void LiveSession::setCamera(const render::CameraState& camera) {
  camera_ = camera;
  cameraChanged_ = true;
}

void LiveSession::setTraceSize(uint32_t width, uint32_t height) {
  const uint32_t w0 = progressive_->targetWidth(), h0 = progressive_->targetHeight();
  // A pixel clicked on the image keeps its point of the scene (the camera's vertical field of view spans the
  // height); one given by number (--set, a script) stays as given.
  if (picked_ && state_.inspectPixel == picked_->pixel && picked_->size == glm::uvec2(w0, h0) &&
      (width != w0 || height != h0)) {
    const double s = double(height) / double(h0);
    const double x = (double(state_.inspectPixel->x) + 0.5 - 0.5 * w0) * s + 0.5 * width;
    const double y = (double(state_.inspectPixel->y) + 0.5 - 0.5 * h0) * s + 0.5 * height;
    if (x >= 0.0 && y >= 0.0 && x < double(width) && y < double(height)) {
      state_.inspectPixel = glm::uvec2(uint32_t(x), uint32_t(y));
      picked_ = Picked{*state_.inspectPixel, glm::uvec2(width, height)};
    }
  }
  progressive_->setTargetSize(width, height);
}

void LiveSession::restartHybrid() {
  ++hybridGeneration_;
  hybridReset_ = Clock::now();
}

void LiveSession::apply(bool waitForMode) {
  auto& tracer = session_->pathTracer();
  auto& st = state_;
  bool restart = false;
  if (cameraChanged_) {
    session_->setCamera(camera_);
    cameraChanged_ = false;
    restart = true;
  }
  if (st.materialsDirty) {
    session_->gpuScene().updateMaterials(st.materials);
    // An edit the specialised shaders compiled out (emission, specular factors) needs the generic build.
    if (!scene::featuresCover(tracer.features(), st.materials)) st.params.render.generic = true;
    st.materialsDirty = false;
    restart = true;
  }
  if (st.lightsDirty) {
    session_->setLights(st.lights);
    st.lightsDirty = false;
    restart = true;
  }
  auto& s = st.params.render;
  auto& a = applied_.params.render;
  const bool envChanged = s.envPath != a.envPath || (s.envPath.empty() && s.envColor != a.envColor);
  if (envChanged) {
    try {
      session_->setEnvironment(s);
      st.envError.clear();
    } catch (const std::exception& e) {
      st.envError = e.what();
      s.envPath = a.envPath;
      s.envColor = a.envColor;
    }
  }
  // The parameters that restart accumulation (render/parameters.h), by what they belong to.
  bool settingsChanged = false, hybridChanged = false;
  for (const auto* p : render::changedParameters(st.params, applied_.params)) {
    if (p->group == "Hybrid") {
      hybridChanged = true;
    } else if (p->name != "mode") {
      settingsChanged = true;
    }
  }
  if (s.denoise != tracer.settings().denoise) {
    // A filter of the accumulation: toggling it restarts nothing (the window writes the AOVs it reads).
    const bool made = tracer.denoiser() != nullptr;
    render::RenderSettings ts = tracer.settings();
    ts.denoise = s.denoise;
    tracer.setSettings(ts);
    if (!made && tracer.denoiser()) loop_->hot().addRenderer(tracer);  // its passes hot-reload too
  }
  if (settingsChanged) {
    tracer.setFeatures(render::featuresFor(session_->scene(), s));
    progressive_->setSettings(s);
    for (auto mode : {render::RenderMode::Hybrid, render::RenderMode::Reflections}) {
      auto* h = session_->rendererFor(mode);
      if (!h) continue;
      render::RenderSettings hs = s;
      hs.width = h->settings().width;
      hs.height = h->settings().height;
      h->setSettings(hs);
    }
    restart = true;
  }
  if (hybridChanged) {
    session_->setHybridSettings(st.params.hybrid);
    restart = true;
  }
  const render::RenderMode shownBefore = session_->mode();
  applyMode(waitForMode);
  const render::RenderMode shown = session_->mode();
  if (applyInspection()) restart = true;
  if (instruments_.apply(tracer, st)) restart = true;  // the cost view's and the asserts' variants
  if (st.referencePath != referenceTried_) {
    referenceTried_ = st.referencePath;
    if (st.referencePath.empty()) {
      liveError_.clearReference();
    } else {
      // A failure is shown in the panel (liveError().error()) and said on the terminal, where --reference was
      // typed.
      if (!liveError_.loadReference(st.referencePath) ||
          (progressive_->samples() > 0 &&
           !liveError_.checkSize(progressive_->targetWidth(), progressive_->targetHeight())))
        std::fprintf(stderr, "workbench: reference %s not used: %s (the running error is a noise estimate)\n",
                     st.referencePath.c_str(), liveError_.error().c_str());
    }
  }
  if (st.resetAccumulation) {
    st.resetAccumulation = false;
    restart = true;
  }
  if (st.reloadShaders) {
    loop_->hot().reloadAll();
    st.reloadShaders = false;
  }
  auto& opts = progressive_->options();
  opts.targetSpp = st.params.render.spp;
  opts.paused = st.paused;
  opts.preview = st.preview;
  opts.budgetMs = st.budgetMs;
  // A rebuild compiling gets the share of the cores the device's policy gives it.
  if (loop_->compiling())
    opts.budgetMs = st.budgetMs * session_->context().policy().windowTraceShareWhileCompiling;
  // The path tracer's accumulation stays while another mode is shown: going back to it resumes the image
  // unless something that alters it changed meanwhile. A hybrid mode restarts with each switch to it.
  const bool pathTracing = shown == render::RenderMode::PathTrace;
  if (!pathTracing && restart) pathTracerStale_ = true;
  const bool restartPathTracer = restart || (pathTracing && shownBefore != shown && pathTracerStale_);
  if (pathTracing) pathTracerStale_ = false;
  const bool restartHybridMode = restart || (!pathTracing && shownBefore != shown);
  if (restartPathTracer) progressive_->invalidate();
  if (restartHybridMode) {
    if (auto* h = session_->hybrid()) {
      h->resetAccumulation();
      ++hybridResets_;
    }
    restartHybrid();
  }
  applyAB();
  applied_ = st;
}

void LiveSession::applyMode(bool wait) {
  if (session_->mode() == state_.params.mode) {
    if (!modeSwitch_.empty()) modeSwitchTimer_.cancelled();  // switched back before the other mode was ready
    modeSwitch_.clear();
    return;
  }
  render::RenderSettings s = state_.params.render;
  s.width = progressive_->targetWidth();
  s.height = progressive_->targetHeight();
  // The other mode's renderer is made off the frame loop; the current mode keeps drawing until it is ready.
  const std::string name = render::renderModeName(state_.params.mode);
  if (!wait && modeSwitch_ != name) {  // a switch the user waits for: timed for the stats
    modeSwitch_ = name;
    modeSwitchTimer_.requested(name, Clock::now());
  }
  if (!wait && !session_->modeReady(state_.params.mode)) {
    session_->prepareMode(state_.params.mode, s);
    return;
  }
  session_->setMode(state_.params.mode, s);
  // A hybrid mode starts its accumulation with the switch: its frames, elapsed time and noise estimate count
  // from here, not from its last reset (before an earlier switch away, or at startup).
  if (auto* h = session_->hybrid()) {
    h->resetAccumulation();
    restartHybrid();
  }
  if (!modeSwitch_.empty()) modeSwitchTimer_.tookEffect(Clock::now());
  modeSwitch_.clear();
}

double LiveSession::modeSwitchSeconds() const {
  return std::chrono::duration<double>(Clock::now() - modeSwitchTimer_.requestTime()).count();
}

bool LiveSession::applyInspection() {
  auto& tracer = session_->pathTracer();
  std::optional<render::InspectRequest> want;
  if (state_.inspectPixel && state_.params.mode == render::RenderMode::PathTrace &&
      state_.inspectPixel->x < progressive_->targetWidth() &&
      state_.inspectPixel->y < progressive_->targetHeight()) {
    render::InspectRequest r;
    r.x = state_.inspectPixel->x;
    r.y = state_.inspectPixel->y;
    r.samples = state_.inspectSamples;
    r.ring = true;  // the latest samples stay; the running estimate sees every one
    want = r;
  }
  // The hybrid renderer of the mode shown records its rays; setting the pixel restarts nothing.
  if (auto* hybrid = session_->hybrid()) {
    std::optional<glm::uvec2> pixel;
    if (state_.inspectPixel && state_.inspectPixel->x < hybrid->settings().width &&
        state_.inspectPixel->y < hybrid->settings().height)
      pixel = state_.inspectPixel;
    if (pixel != hybrid->inspectPixel()) hybrid->setInspectPixel(pixel);
  }
  if (want == tracer.inspection()) return false;
  state_.inspectShown = -1;
  // Another pixel keeps the accumulation (the image does not change); switching the variant restarts it.
  return tracer.setInspection(want);
}

bool LiveSession::takeBackReviewed(bool keepOtherSize) {
  using Slot = render::ProgressiveTracer::ParkSlot;
  if (progressive_->resumeParked(Slot::Review)) {
    if (!keepOtherSize) progressive_->dropParked(Slot::Size);
    return true;
  }
  // Parked at the size shown before Tab: it waits for that size to come back.
  if (progressive_->hasParked(Slot::Review)) progressive_->moveParked(Slot::Review, Slot::Size);
  return false;
}

void LiveSession::applyAB() {
  if (ab_.revertRequested && !ab_.decided && !ab_.installed.empty()) {
    const auto unknown = loop_->revert(ab_.installed);
    // The old pipeline's image is still valid: its accumulation goes on (at once, or when its size comes
    // back); the new pipeline's of another size is not.
    const uint32_t kept = progressive_->parkedSamples(render::ProgressiveTracer::ParkSlot::Review);
    const bool resumed = takeBackReviewed(false);
    std::string files =
        " (the files on disk are unchanged; builds use the old text until you save them again)";
    if (!unknown.empty()) {
      files = " (the files on disk are unchanged; the old text of " + unknown.front().filename().string() +
              (unknown.size() > 1 ? " and " + std::to_string(unknown.size() - 1) + " more" : "") +
              " is no longer known: a variant built later compiles the file on disk)";
    }
    ab_.decide(resumed ? "reverted to the old pipeline and its " + std::to_string(kept) + " samples" + files
                       : "reverted to the old pipeline" + files);
    std::printf("workbench: A/B revert: old pipeline reinstalled\n");
    std::fflush(stdout);
  }
  if (ab_.acceptRequested && !ab_.decided) {
    progressive_->dropParked(render::ProgressiveTracer::ParkSlot::Review);
    ab_.decide("accepted");
  }
  ab_.revertRequested = ab_.acceptRequested = false;
  loop_->setAB(ab_.enabled);
}

void LiveSession::beginFrame() {
  const auto reload = loop_->beginFrame();
  // A new path tracer pipeline: while edits are compared, the old pipeline's accumulation is set aside until
  // the comparison says what becomes of it (Revert or an identical image take it back); otherwise nothing
  // parked (another size's accumulation) belongs to the new pipeline.
  const auto& installed = loop_->hot().lastInstalled();
  if (reload) denoised_ = {};  // a new pipeline (the denoiser's own too) makes the output stale
  if (reload && std::any_of(installed.begin(), installed.end(),
                            [&](const auto& ip) { return ip.owner == &session_->pathTracer(); })) {
    if (ab_.enabled && !session_->hybrid()) {
      progressive_->dropParked(render::ProgressiveTracer::ParkSlot::Size);
      progressive_->parkAccumulation(render::ProgressiveTracer::ParkSlot::Review);
    } else {
      progressive_->dropParked();
    }
  }
  render::HybridRenderer* hybrid = session_->hybrid();
  if (hybrid && (hybrid->settings().width != progressive_->targetWidth() ||
                 hybrid->settings().height != progressive_->targetHeight())) {
    render::RenderSettings hs = state_.params.render;
    hs.width = progressive_->targetWidth();
    hs.height = progressive_->targetHeight();
    hybrid->setSettings(hs);
    restartHybrid();
  }
  if (!hybrid) {
    progressive_->options().stopAtSamples =
        liveError_.nextCheckpoint(progressive_->samples(), progressive_->secondsSinceReset());
    progressive_->beginFrame();
  }
}

bool LiveSession::converging() const {
  return !session_->hybrid() && !state_.paused && !busy() && !progressive_->inPreview() &&
         progressive_->samples() > 0 && !progressive_->done();
}

bool LiveSession::beginTraceOnly(double budgetMs) {
  if (session_->hybrid()) return false;
  progressive_->options().stopAtSamples =
      liveError_.nextCheckpoint(progressive_->samples(), progressive_->secondsSinceReset());
  const double frameBudget = progressive_->options().budgetMs;
  progressive_->options().budgetMs = std::max(frameBudget, budgetMs);
  progressive_->beginFrame();
  if (progressive_->inPreview() || progressive_->done()) {
    progressive_->options().budgetMs = frameBudget;
    return false;
  }
  return true;
}

uint64_t LiveSession::recordTrace(VkCommandBuffer cmd) {
  render::HybridRenderer* hybrid = session_->hybrid();
  lastTraceHybrid_ = hybrid != nullptr;
  if (!hybrid) {
    const uint64_t traced = progressive_->record(cmd);
    progressive_->options().budgetMs = state_.budgetMs;  // after a trace-only submission's larger budget
    if (loop_->compiling())
      progressive_->options().budgetMs =
          state_.budgetMs * session_->context().policy().windowTraceShareWhileCompiling;
    return traced;
  }
  if (!tracing()) return 0;
  hybrid->record(cmd);
  hybrid->advance();
  return uint64_t(hybrid->settings().width) * hybrid->settings().height;
}

bool LiveSession::denoiseValid() const {
  const auto& tracer = session_->pathTracer();
  return tracer.denoiser() && denoised_.generation == progressive_->generation() &&
         denoised_.width == tracer.settings().width && denoised_.height == tracer.settings().height;
}

void LiveSession::planDenoise(bool frameTraces, double secondsSinceInput) {
  const auto& tracer = session_->pathTracer();
  denoiseThisFrame_ = false;
  if (!frameTraces || session_->hybrid() || !tracer.settings().denoise || !tracer.denoiser() ||
      progressive_->inPreview() || progressive_->samples() == 0)
    return;
  if (!denoiseValid()) {
    denoiseThisFrame_ = true;
    return;
  }
  const uint32_t samples = progressive_->samples();
  if (samples == denoised_.samples) return;  // nothing new since (paused, or a slow sample)
  if (state_.paused) {
    denoiseThisFrame_ = true;
    return;
  }
  // Within a share s of the time: at least ms (1/s - 1) since the last run.
  const double sinceMs = std::chrono::duration<double, std::milli>(Clock::now() - denoised_.at).count();
  const auto within = [&](double share) { return sinceMs >= denoised_.ms * (1.0 / share - 1.0); };
  const bool doubled = samples >= 2 * denoised_.samples && secondsSinceInput >= kDenoiseQuietSeconds;
  denoiseThisFrame_ = within(doubled ? kDenoiseShareDoubling : kDenoiseShare);
}

bool LiveSession::denoiseShown() const {
  const auto& tracer = session_->pathTracer();
  return !session_->hybrid() && tracer.settings().denoise && (denoiseThisFrame_ || denoiseValid());
}

bool LiveSession::denoisedAsAsked() const {
  return session_->hybrid() || !session_->pathTracer().settings().denoise ||
         (denoiseValid() && (!state_.paused || denoised_.samples == progressive_->samples()));
}

void LiveSession::recordDenoise(VkCommandBuffer cmd) {
  if (!denoiseThisFrame_) return;
  const auto& tracer = session_->pathTracer();
  tracer.recordDenoise(cmd,
                       progressive_->samples() == 0 ? progressive_->cursorRow() : tracer.settings().height);
  denoised_.generation = progressive_->generation();
  denoised_.width = tracer.settings().width;
  denoised_.height = tracer.settings().height;
  denoised_.samples = progressive_->samples();
  denoised_.at = Clock::now();
  denoiseThisFrame_ = false;
  denoiseInFlight_ = true;
  ++denoiseRuns_;
}

void LiveSession::denoiseTimed(double ms) {
  if (denoiseInFlight_) {
    denoised_.ms = ms;
    instruments_.denoiseTimed(ms);  // the pass table's and pass_ms' "denoise"
  }
  denoiseInFlight_ = false;
}

void LiveSession::traceTimed(uint64_t pixels, double ms) {
  if (!lastTraceHybrid_) progressive_->reportTraceTime(pixels, ms);
  if (progressive_->generation() != traceGeneration_) {
    traceGeneration_ = progressive_->generation();
    traceSeconds_ = 0;
  }
  if (pixels > 0) traceSeconds_ += ms * 1e-3;
}

void LiveSession::frameFinished(Clock::time_point frameBegin) {
  loop_->setABRateHint(progressive_->pixelsPerMs());  // the comparison's first guess of this machine
  loop_->frameFinished(frameBegin);
  for (auto& c : loop_->takeCompleted()) {
    if (!c.abError.empty()) {
      ab_.note = "A/B failed: " + c.abError;
      continue;
    }
    if (c.ab.empty()) continue;
    ab_.set(c.ab, c.installed, c.abPlan, c.event.abMs, c.event.editToFirstFrameMs);
    // The new path tracer renders the very same image as the old one: the old accumulation is its own.
    bool identical = false, other = false;
    for (const auto& o : c.ab) {
      if (o.result.mode != render::renderModeName(render::RenderMode::PathTrace)) continue;
      (o.result.image.verdict == eval::ImageVerdict::Identical ? identical : other) = true;
    }
    const uint32_t kept = progressive_->parkedSamples(render::ProgressiveTracer::ParkSlot::Review);
    if (identical && !other && takeBackReviewed(true))
      ab_.note = "identical image: its " + std::to_string(kept) + " samples go on";
  }
  counters_ = session_->renderer().readCounters();
  instruments_.submissionFinished(session_->renderer());
  instruments_.frameFinished(*session_, !session_->hybrid());
  updateLiveError();
  updateInspection();
}

void LiveSession::traceOnlyFinished() {
  counters_ = session_->renderer().readCounters();
  instruments_.submissionFinished(session_->renderer());
  updateLiveError();
}

uint32_t LiveSession::samples() const {
  if (const auto* h = session_->hybrid()) return h->samplesAccumulated();
  return progressive_->samples();
}

const char* LiveSession::sampleUnit() const {
  return session_->hybrid() ? "frames" : "samples";
}

std::string LiveSession::modeInUse() const {
  const auto* h = session_->hybrid();
  if (!h) return {};
  char buf[96];
  std::snprintf(buf, sizeof buf, "in use: sun angle %.2f deg, AO radius %.3g",
                2.0 * glm::degrees(std::acos(std::clamp(h->sunCosAngle(), -1.0f, 1.0f))), h->aoRadius());
  return buf;
}

bool LiveSession::inPreview() const {
  return !session_->hybrid() && progressive_->inPreview();
}

bool LiveSession::tracing() const {
  if (const auto* h = session_->hybrid())
    return !state_.paused &&
           (state_.params.render.spp == 0 || h->samplesAccumulated() < state_.params.render.spp);
  return !state_.paused && !progressive_->done();
}

bool LiveSession::imageStarted() const {
  if (const auto* h = session_->hybrid()) return h->samplesAccumulated() > 0;
  return progressive_->samples() > 0 || progressive_->cursorRow() > 0 || progressive_->previewValid();
}

bool LiveSession::busy() const {
  return loop_->hot().busy() || !modeSwitch_.empty();
}

double LiveSession::secondsSinceReset() const {
  if (session_->hybrid()) return std::chrono::duration<double>(Clock::now() - hybridReset_).count();
  return progressive_->secondsSinceReset();
}

uint32_t LiveSession::pathTracerSamplesKept() const {
  return session_->mode() != render::RenderMode::PathTrace && !pathTracerStale_ ? progressive_->samples() : 0;
}

uint64_t LiveSession::resets() const {
  return progressive_->resets() + hybridResets_;
}

DisplayFrame LiveSession::displayFrame() const {
  const auto& tracer = session_->pathTracer();
  DisplayFrame d;
  d.albedo = tracer.aovImage(render::Aov::Albedo).view();
  d.normal = tracer.aovImage(render::Aov::Normal).view();
  d.info = tracer.aovImage(render::Aov::Info).view();
  d.stats = tracer.aovImage(render::Aov::Stats).view();
  d.cost = tracer.aovImage(render::Aov::Cost).view();
  d.preview = progressive_->previewImage().view();
  d.maxVertices = float(tracer.settings().maxBounces + 1);
  if (const auto* h = session_->hybrid()) {
    d.radiance = h->outputImage().view();
    d.imageSize = {h->settings().width, h->settings().height};
    d.tracedRows = h->settings().height;
    d.debugViews = false;  // the debug views are the path tracer's AOVs
    return d;
  }
  d.radiance = tracer.accumulationImage().view();
  if (denoiseShown()) d.denoised = tracer.denoiser()->output().view();
  d.imageSize = {tracer.settings().width, tracer.settings().height};
  const bool usePreview = progressive_->previewValid() && progressive_->samples() == 0;
  if (usePreview)
    d.previewSize = {progressive_->previewImage().width(), progressive_->previewImage().height()};
  d.tracedRows = progressive_->samples() == 0 ? progressive_->cursorRow() : tracer.settings().height;
  return d;
}

eval::ImageRGBA LiveSession::image() {
  return session_->image();
}

void LiveSession::updateLiveError() {
  // Called when no frame is in flight. Only whole samples count: the path tracer's accumulation is read when
  // a sample has just finished (the progressive tracer stops at sample ends when a checkpoint is due).
  auto* h = session_->hybrid();
  if (!h && (progressive_->inPreview() || progressive_->cursorRow() != 0)) return;
  if (h && h->samplesAccumulated() < hybridFramesSeen_) ++hybridGeneration_;  // reset by a pipeline install
  if (h) hybridFramesSeen_ = h->samplesAccumulated();
  const uint64_t generation = h ? hybridGeneration_ * 2 + 1 : progressive_->generation() * 2;
  if (generation != errorGeneration_) {
    liveError_.restart();
    errorGeneration_ = generation;
  }
  const uint32_t n = samples();
  const double seconds = secondsSinceReset();
  // The estimator's own image (never the denoised one): the error estimate models its noise.
  if (liveError_.wants(n, seconds)) liveError_.add(session_->renderer().readEstimate(), n, seconds);
}

void LiveSession::updateInspection() {
  // The frame's traces have finished: every sample below the count is complete. The preview's samples are of
  // another resolution: none count.
  const uint32_t finished = progressive_->inPreview() ? 0 : progressive_->samples();
  inspection_.update(session_->pathTracer(), finished, progressive_->generation(), state_.inspectShown);
  // The first sample to arrive is held (the table does not follow the newest under the mouse); the user picks
  // another, or a new pixel starts over.
  if (state_.inspectShown < 0 && !inspection_.samples().empty()) {
    state_.inspectShown = int(inspection_.samples().back().record.sampleIndex);
    inspection_.hold(state_.inspectShown);
  }
  const auto* hybrid = session_->hybrid();
  inspection_.updateHybrid(hybrid && hybrid->inspectPixel() ? std::optional(hybrid->readInspection())
                                                            : std::nullopt);
}

void LiveSession::inspectAt(glm::vec2 rel) {
  if (!state_.inspectOnClick) return;
  const glm::uvec2 size(progressive_->targetWidth(), progressive_->targetHeight());
  state_.inspectPixel = glm::min(glm::uvec2(glm::max(rel, glm::vec2(0.0f)) * glm::vec2(size)), size - 1u);
  picked_ = Picked{*state_.inspectPixel, size};
  state_.inspectOpenPanel = 2;
}

const PixelInspection& LiveSession::inspectionNow() {
  updateInspection();
  return inspection_;
}

}  // namespace wb::live
