#include "app/window/window_command.h"

#include <cstdio>
#include <filesystem>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/cmd_render.h"
#include "common/env.h"
#include "common/file_io.h"
#include "common/paths.h"

namespace wb::app {
namespace {

// Exit status of openWindow() when no window can be opened (no display): run() then renders headless.
constexpr int kNoDisplay = 75;

bool parseWindowSize(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned a = 0, b = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%u%c%u", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a < 64 || b < 64)
    return false;
  w = a;
  h = b;
  return true;
}

// `why` says why when it returns kNoDisplay after a window opened (the device cannot present to it).
int openWindow(const WindowOptions& o, std::string& why) {
  if (!glfwInit()) return kNoDisplay;
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    return kNoDisplay;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window =
      glfwCreateWindow(int(o.windowWidth), int(o.windowHeight), "workbench", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    return kNoDisplay;
  }
  int code = 0;
  try {
    WorkbenchWindow app(window, o);
    code = app.run();
  } catch (const PresentationUnavailable& e) {
    why = e.what();
    code = kNoDisplay;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    code = 1;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace

void WindowCommand::addFlags(CLI::App& cli) {
  app_ = &cli;
  WindowOptions& o = options;
  addRenderOptions(cli, o.render);
  cli.add_option("--window", o.windowSize, "window size WxH")->capture_default_str();
  cli.add_option("--scale", o.scale, "trace resolution relative to the view (0.1..2)")->capture_default_str();
  cli.add_option("--frames", o.frames, "render N frames, then exit (with --screenshot: save the last one)");
  cli.add_option("--screenshot", o.screenshot, "PNG of the window (panel included) at exit");
  cli.add_option("--stats", o.statsPath,
                 "JSON statistics at exit (samples, resets, frame times, shader errors)");
  cli.add_option("--reference", o.reference,
                 "converged .exr of the same view: the Stats panel shows the running error against it");
  cli.add_option("--script", o.scriptPath, "run scripted commands (see src/app/window/script.h)");
  cli.add_option("--set", o.sets, "NAME=VALUE setting at start; names: " + live::settingNamesHelp());
  cli.add_option("--imgui-ini", o.imguiIni, "read and write the panel layout in this file (default: none)");
  cli.add_flag("--no-vsync", o.noVsync, "present with MAILBOX/IMMEDIATE instead of FIFO");
  cli.add_option("--out", headlessOut_,
                 "without a display: the image the headless render writes "
                 "(default out/workbench.png)");
}

void WindowCommand::checkFirstWord(const std::string& word) {
  // A first word that is neither a flag, a command nor a file: a mistyped command, not a scene.
  static const char* const kCommands[] = {"render", "shaders", "watch", "converge", "bench", "sweep"};
  if (word.empty() || word[0] == '-') return;
  for (const char* c : kCommands)
    if (word == c) return;
  std::error_code ec;
  if (!std::filesystem::exists(word, ec) && word.find('/') == std::string::npos &&
      word.find('.') == std::string::npos) {
    throw std::invalid_argument(
        "unknown command '" + word +
        "' (commands: render, shaders, watch, converge, bench, sweep; or a scene file)");
  }
}

void WindowCommand::finish() {
  WindowOptions& o = options;
  o.sizeGiven = app_ && app_->get_option("--size")->count() > 0;
  finishRenderOptions(o.render);
  if (!parseWindowSize(o.windowSize, o.windowWidth, o.windowHeight))
    throw std::invalid_argument("--window: expected WxH (at least 64x64), got '" + o.windowSize + "'");
  if (!(o.scale > 0.0f && o.scale <= 2.0f)) throw std::invalid_argument("--scale: expected 0 < scale <= 2");
  if (app_ && app_->get_option("--frames")->count() > 0 && o.frames == 0)
    throw std::invalid_argument("--frames: at least 1 (without it the window runs until it is closed)");
  // Files written at exit are checked now, not after the session.
  if (!o.screenshot.empty()) requireWritableFile(o.screenshot, "--screenshot");
  if (!o.statsPath.empty()) requireWritableFile(o.statsPath, "--stats");
  // The script is read now (a bad line is refused before the window opens), and the files it writes are
  // checked as the flags' are.
  if (!o.scriptPath.empty()) {
    for (const auto& out : Script::fromFile(o.scriptPath).outputs()) requireWritableFile(out.path, out.what);
  }
}

int WindowCommand::run() {
  const auto display = env::get("DISPLAY"), wayland = env::get("WAYLAND_DISPLAY");
  if (!display && !wayland) return runHeadless("no display (DISPLAY is not set)");
  std::string why;
  const int code = openWindow(options, why);
  if (code != kNoDisplay) return code;
  const std::string name = display.value_or(wayland.value_or(""));
  if (!why.empty()) return runHeadless("cannot present to a window on display '" + name + "': " + why);
  return runHeadless("cannot open a window on display '" + name + "'");
}

int WindowCommand::runHeadless(const std::string& why) {
  std::printf("workbench: %s; rendering headless instead\n", why.c_str());
  std::fflush(stdout);
  RenderCommand render;
  render.options = options.render;
  render.args = args;
  if (headlessOut_.empty()) {
    std::filesystem::create_directories(projectRoot() / "out");
    render.out = (projectRoot() / "out" / "workbench.png").string();
  } else {
    render.out = headlessOut_;
  }
  return render.run();
}

}  // namespace wb::app
