// `workbench shaders [--define K=V]... [--json] PATH...`: compile + reflect shader files or directories.
#pragma once
#include <string>
#include <vector>

namespace wb {

// args = everything after "shaders". Returns the process exit code (non-zero on any failure).
int runShadersCommand(const std::vector<std::string>& args);

}  // namespace wb
