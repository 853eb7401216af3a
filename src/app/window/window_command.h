// The live workbench window: `workbench [SCENE] [render flags] [window flags]`.
#pragma once
#include <string>
#include <vector>

namespace wb::app {

// Exit code runWindowCommand returns when no window can be opened (no display); the caller falls back.
constexpr int kNoDisplay = 75;

int runWindowCommand(const std::vector<std::string>& args);
// The arguments without the window-only flags (for the headless fallback).
std::vector<std::string> renderArgsOnly(const std::vector<std::string>& args);

}  // namespace wb::app
