// `workbench watch [SCENE] --headless [--frames N | --seconds S] [--log FILE.jsonl] [--ab [--ab-size WxH]
// [--ab-spp N] [--ab-rounds N] [--ab-diff-dir DIR]]`: renders continuously offscreen while watching the
// shaders; one JSON line per reload, with the A/B comparison of old and new pipelines under --ab.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"
#include "app/render_options.h"

namespace wb::app {

class WatchCommand : public Command {
 public:
  WatchCommand() { options.size = "256x256"; }
  const char* name() const override { return "watch"; }
  const char* description() const override {
    return "Render continuously offscreen while watching the shaders; log every reload";
  }
  void addFlags(CLI::App& app) override;
  void finish() override { finishRenderOptions(options); }
  int run() override;

  RenderOptions options;
  bool headless = false;
  uint64_t frames = 0;
  double seconds = 0;
  std::string logPath;
  // The A/B comparison after each reload (render/ab_comparison.h).
  bool ab = false;
  std::string abSize = "64x64";
  uint32_t abSpp = 4;
  uint32_t abRounds = 5;
  std::string abDiffDir;  // non-empty: each comparison's old, new and difference images (EXR) go there
};

int runWatchCommand(const std::vector<std::string>& args);

}  // namespace wb::app
