// The live workbench window: it presents a live session (live/live_session.h, which decides everything about
// rendering) and runs the frame loop. Its parts: Presenter (swapchain, display pass, ImGui, submissions),
// WindowInput (mouse and keys), the panels (panels.h) and the script it runs (script.h).
// window_command.cpp parses the command line and opens the window.
#pragma once
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render_options.h"
#include "app/window/frame_stats.h"
#include "app/window/input_events.h"
#include "app/window/panels.h"
#include "app/window/presenter.h"
#include "app/window/script.h"
#include "app/window/window_input.h"
#include "live/live_session.h"

struct GLFWwindow;

namespace wb::app {

struct WindowOptions {
  RenderOptions render;
  bool sizeGiven = false;
  std::string windowSize = "1280x720";
  uint32_t windowWidth = 1280, windowHeight = 720;
  uint64_t frames = 0;
  std::string screenshot, statsPath, scriptPath, reference, imguiIni;
  std::vector<std::string> sets;
  float scale = 0.5f;
  bool noVsync = false;
};

class WorkbenchWindow : public ScriptHost {
  using Clock = std::chrono::steady_clock;

 public:
  WorkbenchWindow(GLFWwindow* window, const WindowOptions& o);
  ~WorkbenchWindow() override;
  int run();

  // ScriptHost
  void scriptSet(const std::string& name, const std::string& value) override { session_->set(name, value); }
  void scriptScreenshot(const std::string& path) override { screenshotPath_ = path; }
  // Saved when the line runs (the device is idle at a script step): a `quit` after it cannot lose it, and a
  // failure ends the script.
  void scriptSave(const std::string& base) override;
  void scriptStats(const std::string& path) override { writeStats(path); }
  void scriptOrbit(float dx, float dy) override { input_->orbit(dx, dy); }
  void scriptCommand(const std::string& name) override;
  void scriptResize(int width, int height) override;
  void scriptInspect(const std::string& path) override;
  void scriptSwitchMode(const std::string& mode) override;
  bool modeSwitchPending() const override { return !session_->modeSwitch().empty(); }
  size_t reloadCount() const override { return session_->loop().hot().history().size(); }
  uint32_t samples() const override { return session_->inPreview() ? 0 : session_->samples(); }
  uint64_t clicksPresented() const override { return clickScreenNs_.size(); }
  bool denoisedAsAsked() const override {
    return !presenter_->frameInFlight() && session_->denoisedAsAsked();
  }

 private:
  int frameLoop();
  // The frame loop's parts: waiting for the frame in flight (false: none was); tracing without presenting
  // while converging untouched (false: quit); one script step (false: the session ends); laying out,
  // recording, submitting and presenting one frame.
  bool finishFrame(Clock::time_point frameBegin);
  bool traceWhileConverging(int& exitCode);
  bool stepScript(int& exitCode);
  void drawFrame(float dt);
  // Whether the loop may trace without drawing or presenting: the session converges untouched, no input for
  // a moment, no script command waiting for frames, and the last present recent enough.
  bool traceOnlyAllowed(Clock::time_point now) const;
  // Whether the next frame has nothing new to show.
  bool nothingToDo() const;
  // Takes the input events' flags: true when any input arrived (the user is interacting); a click or a key
  // makes the next frames redraw without tracing.
  bool takeInput();
  // The window's requests that are not the session's: a camera reset, vsync, a save.
  void applyWindowRequests();
  Rect imageRect(const Rect& view) const;
  void writeStats(const std::string& path);

  GLFWwindow* window_;
  WindowOptions options_;
  std::unique_ptr<live::LiveSession> session_;
  std::unique_ptr<InputEvents> events_;  // before the presenter's ImGui: its callbacks chain to these
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<WindowInput> input_;
  bool vsync_ = true;
  Script script_;
  bool hasScript_ = false;
  float panelWidth_ = 0;  // the side panel's width (0: its default); the user resizes it
  std::string screenshotPath_;
  std::string lastSaved_;
  std::string fatalScriptError_;
  FrameStats frames_;
  uint64_t frameCount_ = 0;
  uint64_t traceOnlySubmits_ = 0;
  int redrawOnlyFrames_ = 0;
  // Left clicks (releases ImGui saw) drawn by the frame in flight, and when each click's frame finished
  // (steady clock, ns since its epoch: the same clock in every process on Linux, so that a program sending
  // synthetic clicks can time them to the screen).
  int clicksInFlight_ = 0;
  std::vector<int64_t> clickScreenNs_;
  Clock::time_point lastPresent_ = Clock::now();
  Clock::time_point lastInput_ = Clock::now();
};

}  // namespace wb::app
