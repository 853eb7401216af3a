// The live workbench: `workbench [SCENE] [render flags] [window flags]`, the command run without a
// subcommand. Without a display it says so and renders the scene headless to out/workbench.png.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"
#include "app/window/workbench_window.h"

namespace wb::app {

class WindowCommand : public Command {
 public:
  const char* name() const override { return ""; }
  const char* description() const override {
    return "The live workbench: progressive path tracing in a window with inspection panels and shader hot "
           "reload (headless render without a display). Commands: render, shaders, watch, converge, bench";
  }
  void addFlags(CLI::App& app) override;
  void checkFirstWord(const std::string& word) override;
  void finish() override;
  int run() override;

  WindowOptions options;

 private:
  CLI::App* app_ = nullptr;
  std::string headlessOut_;
  int runHeadless(const std::string& why);
};

}  // namespace wb::app
