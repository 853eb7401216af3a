// `workbench watch [SCENE] --headless [--frames N | --seconds S] [--log FILE.jsonl] [--ab [--ab-size WxH]
// [--ab-spp N] [--ab-rounds N] [--ab-diff-dir DIR]]`: renders continuously offscreen while watching the
// shaders; one JSON line per reload, with the A/B comparison of old and new pipelines under --ab.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"
#include "app/render_options.h"
#include "common/atomic_file.h"

namespace wb::app {

class WatchCommand : public Command {
 public:
  WatchCommand() { options.size = "256x256"; }
  const char* name() const override { return "watch"; }
  const char* description() const override {
    return "Render continuously offscreen while watching the shaders; log every reload";
  }
  void addFlags(CLI::App& app) override;
  // Checks the flags (a count or a duration that never ends, A/B flags without --ab, flags watch has no use
  // for) and the outputs (--log opened, --ab-diff-dir writable) before any work.
  void finish() override;
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
  uint32_t abWidth = 0, abHeight = 0;  // --ab-size, parsed

 private:
  std::vector<CLI::Option*> abOptions_;  // --ab-size, --ab-spp, --ab-rounds, --ab-diff-dir
  CLI::Option* framesOption_ = nullptr;
  CLI::Option* secondsOption_ = nullptr;
  AppendLog log_;
};

int runWatchCommand(const std::vector<std::string>& args);

}  // namespace wb::app
