// `workbench converge [SCENE] (--reference REF.exr | --reference-spp N) [--seconds S] [--runs R]
//  [--config NAME:FLAGS]... --out DIR [render flags]`: progressive renders of each configuration with
// error-against-reference checkpoints; writes converge.csv, converge.png (gnuplot), converge.md and error
// images to DIR. `--hard-cases` renders the built-in numerical hard-case scenes instead and writes
// hard_cases.md.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/converge_report.h"
#include "app/render_options.h"
#include "render/parameters.h"
#include "scene/hard_cases.h"

namespace wb::app {

// One configuration: its name and render flags (which win over the command's).
struct ConvergeConfig {
  std::string name;
  std::vector<std::string> flags;
  RenderOptions options;
};

class ConvergeCommand : public Command {
 public:
  const char* name() const override { return "converge"; }
  const char* description() const override {
    return "Render configurations progressively and measure error against a reference over time";
  }
  void addFlags(CLI::App& app) override;
  void finish() override;
  int run() override;

  RenderOptions base;
  ConvergeOptions converge;
  std::vector<ConvergeConfig> configs;

 private:
  int runHardCases();
  CLI::Option* referenceSppOption_ = nullptr;
  std::optional<eval::ImageRGBA> referenceImage_;  // --reference, read by finish()
};

int runConvergeCommand(const std::vector<std::string>& args);

// A hard case's settings over `params` (a variant's flags) through the parameter registry, then its lower
// bound on max_bounces. Throws std::invalid_argument on a setting the registry refuses.
void applyHardCase(const scene::HardCase& hc, render::Parameters& params);

}  // namespace wb::app
