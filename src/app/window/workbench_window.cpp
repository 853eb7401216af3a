#include "app/window/workbench_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "app/progress.h"
#include "app/window/ab_panel.h"
#include "app/window/widget_rects.h"
#include "app/window/window_report.h"
#include "common/json_text.h"

namespace wb::app {
namespace {

// While converging untouched, the image is presented this often; between presents the loop only traces.
constexpr double kIdlePresentSeconds = 1.0;
// Input within this long keeps every frame presented (the user is interacting).
constexpr double kInteractionSeconds = 0.5;
// The trace time of one trace-only submission: input that arrives meanwhile waits at most this long.
constexpr double kTraceOnlyBudgetMs = 50.0;
// Frames drawn without a trace after a click or a key: ImGui acts on a click in the frame after the one that
// saw its press when both came between two frames.
constexpr int kRedrawOnlyFrames = 2;

double secondsBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

live::LiveSession::Options sessionOptions(GLFWwindow* window, const WindowOptions& o) {
  live::LiveSession::Options so;
  auto& st = so.state;
  st.params = o.render.params;
  st.params.render.denoise = true;  // the window's view is denoised (the panel's toggle, `--set denoise=0`)
  // The target spp: --spp when given, else keep refining.
  st.params.render.spp = o.render.flags.given("spp") ? o.render.params.render.spp : 0;
  st.resolutionScale = o.scale;
  st.fixedSize = o.sizeGiven;
  st.fixedWidth = o.render.params.render.width;
  st.fixedHeight = o.render.params.render.height;
  st.vsync = !o.noVsync;
  st.referencePath = o.reference;
  (void)window;
  uint32_t extCount = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&extCount);
  if (!exts) throw std::runtime_error("GLFW found no Vulkan surface support on this display");
  so.session.scenePath = o.render.scene;
  so.session.context.deviceName = o.render.device;
  so.session.context.instanceExtensions.assign(exts, exts + extCount);
  so.session.context.presentation = true;
  return so;
}

}  // namespace

WorkbenchWindow::WorkbenchWindow(GLFWwindow* window, const WindowOptions& o)
    : window_(window), options_(o), vsync_(!o.noVsync), panelWidth_(sidePanelWidth(float(o.windowWidth))) {
  session_ = std::make_unique<live::LiveSession>(sessionOptions(window, o));
  events_ = std::make_unique<InputEvents>(window_);  // first: ImGui's backend chains its callbacks to these
  presenter_ = std::make_unique<Presenter>(session_->render().context(), session_->render().library(),
                                           window_, vsync_, o.imguiIni);
  input_ = std::make_unique<WindowInput>(window_, *events_, *session_);
  presenter_->setFrameLimit([this] { return session_->loop().frameLimit(); },
                            [this] { return session_->loop().compilingFrameLimit(); });
  presenter_->setHangMessage([this](double seconds) { return session_->loop().hangMessage(seconds); });
  session_->loop().addPass(presenter_->display().pass());
  session_->start(
      [] { glfwPostEmptyEvent(); });  // ends a rest or an idle wait: the build is committed at once
  for (const auto& s : o.sets) {
    const auto nameValue = render::splitAssignment(s);
    if (!nameValue) throw std::invalid_argument("--set: expected NAME=VALUE, got '" + s + "'");
    live::applySetting(session_->state(), nameValue->first, nameValue->second);
  }
  if (!o.scriptPath.empty()) {
    script_ = Script::fromFile(o.scriptPath);
    hasScript_ = true;
  }
}

WorkbenchWindow::~WorkbenchWindow() {
  if (session_) session_->loop().hot().stop();
  input_.reset();
  presenter_.reset();  // its display pass is one of the loop's passes: the loop stops reloading first
  events_.reset();
  session_.reset();
}

void WorkbenchWindow::scriptCommand(const std::string& name) {
  auto& st = session_->state();
  if (name == "reset_camera") st.resetCamera = true;
  if (name == "reset") st.resetAccumulation = true;
  if (name == "reload") st.reloadShaders = true;
  if (name == "quit") st.quit = true;
  if (name == "ab_revert") session_->ab().revertRequested = true;
  if (name == "ab_accept") session_->ab().acceptRequested = true;
}

void WorkbenchWindow::scriptSave(const std::string& base) {
  lastSaved_ = saveRender(*session_, input_->camera(), base);
}

void WorkbenchWindow::scriptResize(int width, int height) {
  glfwSetWindowSize(window_, width, height);
}

void WorkbenchWindow::scriptInspect(const std::string& path) {
  writeInspection(*session_, path);
}

void WorkbenchWindow::scriptSwitchMode(const std::string& mode) {
  live::applySetting(session_->state(), "mode", mode);
  session_->apply();  // starts the switch; the frames that follow complete it
}

void WorkbenchWindow::writeStats(const std::string& path) {
  nlohmann::json j = sessionStatsJson(*session_);
  j["frames"] = frameCount_;
  j["trace_only_submits"] = traceOnlySubmits_;  // trace submissions between presents while converging
  j["key_presses"] = input_->keyPresses();      // the window's keys (F5, F12, Tab, Home) acted on
  j["panel_visible"] = session_->state().showPanel;
  j["preview_enabled"] = session_->state().preview;  // the "preview after changes" checkbox
  j["clicks_presented"] = clickScreenNs_.size();
  j["click_screen_ns"] = clickScreenNs_;              // when each click's frame finished (steady clock, ns)
  j["click_event_ns"] = events_->leftReleaseTimes();  // when the loop received each click's release
  nlohmann::json widgets = nlohmann::json::object();
  for (const auto& [name, r] : widgetRects().rects()) widgets[name] = {r.x, r.y, r.w, r.h};
  j["widgets"] = widgets;  // where the last frame drew them (framebuffer pixels)
  auto object = [](const std::optional<PickResult>& p) {
    return p ? nlohmann::json{{"instance", p->instance},
                              {"node", p->nodeName},
                              {"material", p->material},
                              {"material_name", p->materialName}}
             : nlohmann::json(nullptr);
  };
  j["selected_object"] = object(input_->selected());  // the material editor's
  j["hover_object"] = object(input_->hover());
  const auto& sc = presenter_->swapchain();
  j["window_width"] = sc.extent().width;
  j["window_height"] = sc.extent().height;
  j["present_mode"] = vk::presentModeName(sc.presentMode());
  j["frame_ms"] = {
      {"last", frames_.last()},           {"mean", frames_.mean()}, {"p50", frames_.percentile(0.5f)},
      {"p95", frames_.percentile(0.95f)}, {"max", frames_.max()},   {"count", frames_.count()}};
  j["trace_gpu_ms_last"] = presenter_->traceMs();
  j["denoise_gpu_ms_last"] = presenter_->afterTraceMs();
  j["denoise_runs"] = session_->denoiseRuns();
  j["display_gpu_ms_last"] = presenter_->displayMs();
  j["pass_ms"]["display"] = presenter_->displayMs();  // beside the renderer's passes and the denoiser
  j["parameters"] = parametersJson(*session_, input_->camera());
  writeJsonFile(path, j, "stats");
}

Rect WorkbenchWindow::imageRect(const Rect& view) const {
  const float tw = float(session_->traceWidth()), th = float(session_->traceHeight());
  const float scale = std::min(view.w / tw, view.h / th);
  const float w = std::max(1.0f, std::floor(tw * scale)), h = std::max(1.0f, std::floor(th * scale));
  return {std::floor(view.x + (view.w - w) * 0.5f), std::floor(view.y + (view.h - h) * 0.5f), w, h};
}

bool WorkbenchWindow::finishFrame(Clock::time_point frameBegin) {
  if (!presenter_->finish()) return false;
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  for (; clicksInFlight_ > 0; --clicksInFlight_) clickScreenNs_.push_back(now);
  session_->traceTimed(presenter_->tracedPixels(), presenter_->traceMs());
  session_->denoiseTimed(presenter_->afterTraceMs());
  session_->frameFinished(frameBegin);
  // While a rebuild compiles on a CPU device, the loop rests after each frame so the compile gets most of the
  // cores: the panel and the present cost CPU time besides the trace budget.
  const auto until = session_->loop().restUntil(frameBegin, Clock::now(),
                                                session_->render().context().policy().windowRestRatio);
  // Input still wakes the loop's event queue; it is handled with the next frame.
  for (auto t = Clock::now(); session_->loop().compiling() && t < until; t = Clock::now())
    glfwWaitEventsTimeout(std::chrono::duration<double>(until - t).count());
  return true;
}

bool WorkbenchWindow::traceOnlyAllowed(Clock::time_point now) const {
  if (!session_->converging() || input_->dragging()) return false;
  if (!screenshotPath_.empty() || session_->state().saveRequest) return false;
  if (hasScript_ && !script_.waitingForEvent()) return false;
  if (secondsBetween(lastInput_, now) < kInteractionSeconds) return false;
  return secondsBetween(lastPresent_, now) < kIdlePresentSeconds;
}

bool WorkbenchWindow::traceWhileConverging(int& exitCode) {
  // Input, a rebuild or a script step ends it at once; the script's waits are checked after each submission.
  while (!presenter_->frameInFlight() && traceOnlyAllowed(Clock::now()) &&
         session_->beginTraceOnly(kTraceOnlyBudgetMs) &&
         presenter_->traceOnly([&](VkCommandBuffer cmd) { return session_->recordTrace(cmd); })) {
    session_->traceTimed(presenter_->tracedPixels(), presenter_->traceMs());
    session_->traceOnlyFinished();
    ++traceOnlySubmits_;
    glfwPollEvents();
    if (takeInput()) break;
    if (hasScript_) {
      try {
        if (!script_.step(*this, true) || !script_.waitingForEvent()) break;
      } catch (const std::exception& e) {
        fatalScriptError_ = e.what();
        exitCode = 1;
        return false;
      }
    }
  }
  return !session_->state().quit;
}

bool WorkbenchWindow::takeInput() {
  if (events_->takeDiscrete()) redrawOnlyFrames_ = kRedrawOnlyFrames;
  if (!events_->takeActivity()) return false;
  lastInput_ = Clock::now();
  return true;
}

bool WorkbenchWindow::nothingToDo() const {
  return !session_->tracing() && !session_->busy() && !input_->dragging() && screenshotPath_.empty() &&
         !session_->state().saveRequest && (!hasScript_ || script_.waitingForEvent()) && !options_.frames;
}

bool WorkbenchWindow::stepScript(int& exitCode) {
  if (!hasScript_ || !screenshotPath_.empty()) return true;  // a requested screenshot is drawn first
  try {
    // A finished script still lets a requested screenshot reach the screen.
    return script_.step(*this) || options_.frames || !screenshotPath_.empty();
  } catch (const std::exception& e) {
    fatalScriptError_ = e.what();
    exitCode = 1;
    return false;
  }
}

void WorkbenchWindow::applyWindowRequests() {
  auto& st = session_->state();
  if (st.resetCamera) {
    input_->resetCamera();
    st.resetCamera = false;
  }
  if (st.vsync != vsync_) {
    vsync_ = st.vsync;
    presenter_->setVsync(vsync_);
  }
}

void WorkbenchWindow::drawFrame(float dt) {
  if (!presenter_->beginFrame()) return;
  widgetRects().beginFrame();
  // A click's release reaches ImGui in this frame: its widget acts now, and the frame shows it.
  const int clicks = ImGui::GetIO().MouseReleased[ImGuiMouseButton_Left] ? 1 : 0;
  auto& st = session_->state();
  const auto& sc = presenter_->swapchain();
  PanelContext pc{*session_,          input_->camera(), input_->hover(),
                  input_->selected(), frames_,          vk::presentModeName(sc.presentMode()),
                  lastSaved_};
  pc.displayGpuMs = presenter_->displayMs();
  const float W = float(sc.extent().width), H = float(sc.extent().height);
  // Input first, in the layout of the last frame (ImGui's widgets take their clicks while the panel is laid
  // out): what it changes (a picked pixel, the selection, Tab) is drawn in this frame.
  const float shownPanel = st.showPanel ? panelWidth_ : 0.0f;
  const Rect inputView{shownPanel, 0.0f, std::max(W - shownPanel, 1.0f), H};
  input_->handle(inputView, imageRect(inputView), dt);
  const float panelWidth = drawSidePanel(pc, W, H, panelWidth_);
  const Rect view{panelWidth, 0.0f, std::max(W - panelWidth, 1.0f), H};
  drawOverlays(pc, imageRect(view));
  widgetRects().note("image", imageRect(view));
  // Tab hides every panel: the image has the window.
  if (st.showPanel) drawABPanel(session_->ab(), render::renderModeName(session_->mode()), W, H);

  // The trace resolution follows the view beside the panel (times the resolution scale) unless --size fixed
  // it: hiding the panel (Tab) gives the image the whole window (the session resumes the other size's
  // accumulation when the panel comes back).
  if (st.fixedSize) {
    session_->setTraceSize(uint32_t(std::lround(st.fixedWidth * st.resolutionScale)),
                           uint32_t(std::lround(st.fixedHeight * st.resolutionScale)));
  } else {
    session_->setTraceSize(uint32_t(std::lround(view.w * st.resolutionScale)),
                           uint32_t(std::lround(view.h * st.resolutionScale)));
  }
  applyWindowRequests();
  session_->apply();
  if (st.saveRequest) {
    try {
      lastSaved_ = saveRender(*session_, input_->camera(), *st.saveRequest);
    } catch (const std::exception& e) {
      lastSaved_ = std::string("save failed: ") + e.what();
    }
    st.saveRequest.reset();
  }
  session_->beginFrame();
  // After a click or a key the next frames redraw without tracing (their effect is on screen a display pass
  // later), unless the image has nothing to show yet. The denoiser runs only in frames that trace.
  const bool trace = redrawOnlyFrames_ == 0 || !session_->imageStarted();
  if (redrawOnlyFrames_ > 0) --redrawOnlyFrames_;
  session_->planDenoise(trace, secondsBetween(lastInput_, Clock::now()));
  const live::DisplayFrame d = session_->displayFrame();
  presenter_->display().setSources(
      {d.radiance, d.albedo, d.normal, d.info, d.preview, d.stats, d.cost, d.denoised});

  const Rect image = imageRect(view);
  gpu::DisplayPush push{};
  push.viewRect = {image.x, image.y, image.w, image.h};
  push.imageSize = d.imageSize;
  push.previewSize = d.previewSize;
  push.exposureScale = std::exp2(st.params.display.exposure);
  push.tonemap = uint32_t(st.params.display.tonemap);
  push.view = d.debugViews ? st.params.display.view : WB_VIEW_BEAUTY;
  push.encodeSrgb = sc.formatIsSrgb() ? 0u : 1u;
  push.tracedRows = d.tracedRows;
  push.sceneScale = sceneRadius(session_->render().scene());
  push.maxVertices = d.maxVertices;
  if (const auto& cost = session_->instruments().cost(); cost && cost->valid()) {
    push.costFull = float(cost->p95);
    push.inefficiencyFull = float(cost->inefficiencyP95);
    push.costMedian = cost->estimate == eval::CostEstimate::Median ? 1u : 0u;
  }
  push.denoiseSplit = d.denoised ? st.params.display.denoiseSplit : -1.0f;

  const bool lastFrame = options_.frames && frameCount_ + 1 >= options_.frames;
  std::string screenshot;
  if (!screenshotPath_.empty() || (lastFrame && !options_.screenshot.empty()))
    screenshot = screenshotPath_.empty() ? options_.screenshot : screenshotPath_;
  const auto recordTrace = [&](VkCommandBuffer cmd) -> uint64_t {
    return trace ? session_->recordTrace(cmd) : 0;
  };
  const auto recordDenoise = [&](VkCommandBuffer cmd) { session_->recordDenoise(cmd); };
  if (!presenter_->present(recordTrace, recordDenoise, push, screenshot)) return;
  screenshotPath_.clear();
  clicksInFlight_ += clicks;
  lastPresent_ = Clock::now();
  ++frameCount_;
}

int WorkbenchWindow::run() {
  try {
    return frameLoop();
  } catch (const FrameHang& hang) {
    // Say which edit did it, and end (the watchdog does the same where the frame loop is blocked).
    Presenter::endForHang(session_->loop().hangMessage(hang.seconds));
  }
}

int WorkbenchWindow::frameLoop() {
  // SIGINT/SIGTERM end the session like the quit key, after the frame in flight (or, should it never finish,
  // the process).
  InterruptRequest interrupt;
  auto last = Clock::now();
  auto frameBegin = last;  // when the work of the frame in flight began (after any rest)
  int exitCode = 0;
  while (!glfwWindowShouldClose(window_) && !session_->state().quit && !interrupt.requested()) {
    glfwPollEvents();
    finishFrame(frameBegin);
    takeInput();
    // Converging untouched: trace without drawing or presenting until the next present is due.
    if (!traceWhileConverging(exitCode)) break;
    // Nothing to trace and nothing happening: sleep until input (or a short timeout for the panel's clocks
    // and the script's waits) instead of redrawing the same frame.
    if (!presenter_->frameInFlight() && nothingToDo() &&
        secondsBetween(lastInput_, Clock::now()) > kInteractionSeconds) {
      glfwWaitEventsTimeout(0.25);
      takeInput();
    }
    const auto now = Clock::now();
    const float dt = std::chrono::duration<float>(now - last).count();
    if (frameCount_ > 0) {
      frames_.add(std::chrono::duration<float, std::milli>(now - last).count());
      session_->frameInterval(last, now);
      interrupt.noteWorkSeconds(std::chrono::duration<double>(now - last).count());
    }
    last = now;
    frameBegin = now;

    if (options_.frames && frameCount_ >= options_.frames) break;
    if (!stepScript(exitCode)) break;
    drawFrame(dt);
  }
  if (presenter_->finish()) session_->traceOnlyFinished();
  if (!options_.statsPath.empty()) writeStats(options_.statsPath);
  std::printf("workbench: %llu frames, %u samples, frame time mean %.1f ms (p95 %.1f ms)\n",
              static_cast<unsigned long long>(frameCount_), session_->progressive().samples(), frames_.mean(),
              frames_.percentile(0.95f));
  if (!fatalScriptError_.empty())
    std::fprintf(stderr, "workbench: script error: %s\n", fatalScriptError_.c_str());
  return exitCode;
}

}  // namespace wb::app
