#include "app/window/window_command.h"

#include <cstdio>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/window/workbench_window.h"
#include "common/file_io.h"

namespace wb::app {
namespace {

const std::vector<std::string> kWindowValueFlags = {"--frames", "--screenshot", "--stats", "--script",
                                                    "--set",    "--window",     "--scale", "--imgui-ini"};
const std::vector<std::string> kWindowBoolFlags = {"--no-vsync"};

bool parseWindowSize(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned a = 0, b = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%u%c%u", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a < 64 || b < 64)
    return false;
  w = a;
  h = b;
  return true;
}

}  // namespace

std::vector<std::string> renderArgsOnly(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (size_t i = 0; i < args.size(); ++i) {
    const auto& a = args[i];
    bool skip = false;
    for (const auto& f : kWindowValueFlags) {
      if (a == f) {
        skip = true;
        ++i;  // its value too
      } else if (a.rfind(f + "=", 0) == 0) {
        skip = true;
      }
    }
    for (const auto& f : kWindowBoolFlags) skip = skip || a == f;
    if (!skip) out.push_back(a);
  }
  return out;
}

int runWindowCommand(const std::vector<std::string>& args) {
  CLI::App cli(
      "The live workbench: progressive path tracing in a window with inspection panels and shader hot "
      "reload",
      "workbench");
  WindowOptions o;
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
  cli.add_option("--set", o.sets, std::string("NAME=VALUE setting at start; names: ") + settingNamesHelp());
  cli.add_option("--imgui-ini", o.imguiIni, "read and write the panel layout in this file (default: none)");
  cli.add_flag("--no-vsync", o.noVsync, "present with MAILBOX/IMMEDIATE instead of FIFO");
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    cli.parse(reversed);
    o.sizeGiven = cli.get_option("--size")->count() > 0;
    o.sppGiven = cli.get_option("--spp")->count() > 0;
    finishRenderOptions(o.render);
    if (!parseWindowSize(o.windowSize, o.windowWidth, o.windowHeight))
      throw std::invalid_argument("--window: expected WxH (at least 64x64), got '" + o.windowSize + "'");
    if (!(o.scale > 0.0f && o.scale <= 2.0f)) throw std::invalid_argument("--scale: expected 0 < scale <= 2");
    // Files written at exit are checked now, not after the session.
    if (!o.screenshot.empty()) requireWritableFile(o.screenshot, "--screenshot");
    if (!o.statsPath.empty()) requireWritableFile(o.statsPath, "--stats");
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", cli.help().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    return 2;
  }

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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    code = 1;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace wb::app
