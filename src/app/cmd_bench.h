// `workbench bench [--quick] [--only SECTIONS] [--out FILE.json]`: the performance suite (path tracer rates
// per scene, specialised vs generic; acceleration-structure builds; memory; cold/warm start-up; hot-reload
// latency; the modes' speed against error; the live window's rate, edit latency and input). Not a test.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"

namespace wb::app {

class BenchCommand : public Command {
 public:
  const char* name() const override { return "bench"; }
  const char* description() const override {
    return "Performance suite: path tracer rates, start-up, hot reload, modes, window (not a test)";
  }
  void addFlags(CLI::App& app) override;
  void finish() override;
  int run() override;

  static const std::vector<std::string>& sectionNames();
  bool quick = false;
  std::string out, device, size;
  std::vector<std::string> rooflineSizes;  // --roofline-sizes (empty: the defaults, set by finish())
  bool rooflineSizesGiven = false;
  int repeats = 0;
  int edits = 0;
  bool noLoad = false;
  int clicks = -1;  // window: synthetic clicks (-1: the default)
  std::vector<std::string> sections = sectionNames();
};

int runBenchCommand(const std::vector<std::string>& args);

}  // namespace wb::app
