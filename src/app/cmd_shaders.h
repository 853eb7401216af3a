// `workbench shaders [--define K=V]... [--json] PATH...`: compile + reflect shader files or directories.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"

namespace wb::app {

class ShadersCommand : public Command {
 public:
  const char* name() const override { return "shaders"; }
  const char* description() const override {
    return "Compile and reflect shaders (files, or directories searched recursively for stage files)";
  }
  void addFlags(CLI::App& app) override;
  int run() override;

  std::vector<std::string> defines, paths;
  bool json = false, noCache = false, optimize = false;
};

// args = everything after "shaders". Returns the process exit code (non-zero on any failure).
int runShadersCommand(const std::vector<std::string>& args);

}  // namespace wb::app
