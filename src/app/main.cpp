// workbench: the Vulkan ray tracing shader workbench. Subcommands: render, shaders (and the live window when
// run with no subcommand).
#include <csignal>
#include <cstdio>
#include <cstring>

#include <execinfo.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cmd_bench.h"
#include "app/cmd_converge.h"
#include "app/cmd_render.h"
#include "app/cmd_shaders.h"
#include "app/cmd_watch.h"
#include "app/window/window_command.h"
#include "common/paths.h"
#include "vk/context.h"

namespace {

#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer reports crashes itself
// A crash still says where: the call stack (addresses relative to the binary's load address, for addr2line)
// goes to stderr before the default action ends the process.
void crashHandler(int sig) {
  void* frames[64];
  const int n = backtrace(frames, 64);
  const char* head =
      sig == SIGSEGV ? "workbench: segmentation fault; stack:\n" : "workbench: fatal signal; stack:\n";
  (void)!write(2, head, std::strlen(head));
  backtrace_symbols_fd(frames, n, 2);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
#endif

void usage() {
  std::printf(
      "usage: workbench [SCENE] [render flags]        the live workbench (headless render without a "
      "display)\n"
      "       workbench render [SCENE] --out FILE ...  headless render (PNG tonemapped, EXR linear)\n"
      "       workbench shaders [--json] PATH...       compile and reflect shaders\n"
      "       workbench watch [SCENE] --headless ...   render while hot-reloading shaders; log reloads\n"
      "       workbench converge [SCENE] --out DIR ... error against a reference over time, per config\n"
      "       workbench bench [--quick] [--out FILE]   performance suite (not a test)\n"
      "run 'workbench COMMAND --help' for a command's flags\n");
}

// The first word of the live workbench's command line is a scene: an existing file, or a name that looks like
// a glTF path (the loader then says what is wrong with it).
bool looksLikeScene(const std::string& word) {
  std::error_code ec;
  if (std::filesystem::exists(word, ec)) return true;
  const std::string ext = std::filesystem::path(word).extension().string();
  return ext == ".gltf" || ext == ".glb" || word.find('/') != std::string::npos;
}

int runDefault(const std::vector<std::string>& args) {
  // The live window; without a display, say so and fall back to a headless render of the scene.
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland)) {
    const int code = wb::app::runWindowCommand(args);
    if (code != wb::app::kNoDisplay) return code;
    std::printf("workbench: cannot open a window on display '%s'; rendering headless instead\n",
                display ? display : wayland);
  } else {
    std::printf("workbench: no display (DISPLAY is not set); rendering headless instead\n");
  }
  std::vector<std::string> renderArgs = wb::app::renderArgsOnly(args);
  bool hasOut = false;
  for (const auto& a : renderArgs) hasOut = hasOut || a == "--out" || a.rfind("--out=", 0) == 0;
  const std::string out = (wb::projectRoot() / "out" / "workbench.png").string();
  if (!hasOut) {
    std::filesystem::create_directories(wb::projectRoot() / "out");
    renderArgs.push_back("--out");
    renderArgs.push_back(out);
  }
  return wb::app::runRenderCommand(renderArgs);
}

}  // namespace

int main(int argc, char** argv) {
#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer reports crashes itself
  std::signal(SIGSEGV, crashHandler);
  std::signal(SIGBUS, crashHandler);
  std::signal(SIGILL, crashHandler);
  std::signal(SIGFPE, crashHandler);
#endif
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h" || args[0] == "help")) {
    usage();
    return 0;
  }
  const std::string cmd = args.empty() ? "" : args[0];
  std::vector<std::string> rest =
      args.empty() ? args : std::vector<std::string>(args.begin() + 1, args.end());
  int code = 0;
  if (cmd == "render") {
    code = wb::app::runRenderCommand(rest);
  } else if (cmd == "shaders") {
    code = wb::runShadersCommand(rest);
  } else if (cmd == "watch") {
    code = wb::app::runWatchCommand(rest);
  } else if (cmd == "converge") {
    code = wb::app::runConvergeCommand(rest);
  } else if (cmd == "bench") {
    code = wb::app::runBenchCommand(rest);
  } else if (!cmd.empty() && cmd[0] != '-' && !looksLikeScene(cmd)) {
    // A typo of a command ("shader") must not be taken for a scene path.
    std::fprintf(stderr,
                 "workbench: unknown command '%s' (commands: render, shaders, watch, converge, bench; or a "
                 "scene file: workbench SCENE.gltf)\n",
                 cmd.c_str());
    return 2;
  } else {
    code = runDefault(args);
  }
  // With the validation layer on (WB_VALIDATION=1, as in the tests), a validation error is a bug: the exit
  // status says so even when the command itself succeeded.
  const uint32_t validationErrors = wb::vk::Context::processValidationErrors();
  if (code == 0 && validationErrors > 0) {
    std::fprintf(stderr, "workbench: %u Vulkan validation error(s), printed above\n", validationErrors);
    code = 3;
  }
  return code;
}
