// workbench: the Vulkan ray tracing shader workbench. One command line: the live window without a
// subcommand; render, shaders, watch, converge, bench and sweep as subcommands (app/command.h).
#include <cstdio>
#include <string>
#include <vector>

#include "app/cmd_bench.h"
#include "app/cmd_converge.h"
#include "app/cmd_render.h"
#include "app/cmd_shaders.h"
#include "app/cmd_watch.h"
#include "app/sweep/cmd_sweep.h"
#include "app/window/window_command.h"
#include "common/crash_report.h"
#include "common/env.h"
#include "common/paths.h"
#include "vk/context.h"
#include "vk/driver_policy.h"

int main(int argc, char** argv) {
  // A crash (a driver's compiler that aborts, a segmentation fault) still says where.
  wb::installCrashReport("workbench");
  // The environment is checked before anything else: a variable with a value it cannot take is refused
  // naming it, as a bad flag is (exit status 2), instead of meaning the default, or crashing the driver.
  try {
    wb::env::checkWorkbenchVariables();
    wb::vk::checkDriverEnvironment();
    (void)wb::projectRoot();  // WB_ROOT
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    return wb::app::kUsageError;
  }
  const std::vector<std::string> args(argv + 1, argv + argc);
  wb::app::WindowCommand window;
  wb::app::RenderCommand render;
  wb::app::ShadersCommand shaders;
  wb::app::WatchCommand watch;
  wb::app::ConvergeCommand converge;
  wb::app::BenchCommand bench;
  wb::app::SweepCommand sweep;
  const std::vector<wb::app::Command*> subcommands = {&render, &shaders, &watch, &converge, &bench, &sweep};
  CLI::App app(window.description(), "workbench");
  window.addFlags(app);
  for (auto* c : subcommands) c->addFlags(*app.add_subcommand(c->name(), c->description()));
  app.require_subcommand(0, 1);
  int code = wb::app::parseAndRun(app, args, &window, subcommands);
  // With the validation layer on (WB_VALIDATION=1, as in the tests), a validation error is a bug: the exit
  // status says so even when the command itself succeeded.
  const uint32_t validationErrors = wb::vk::Context::processValidationErrors();
  if (code == 0 && validationErrors > 0) {
    std::fprintf(stderr, "workbench: %u Vulkan validation error(s), printed above\n", validationErrors);
    code = 3;
  }
  // A device that never finished a frame (an endless loop in a shader, refused at its trial) still has
  // threads running it; the drivers' exit handlers could wait for them forever.
  if (wb::vk::Context::anyHung()) {
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(code);
  }
  return code;
}
