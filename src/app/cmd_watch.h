#pragma once
#include <string>
#include <vector>

namespace wb::app {

// `workbench watch [SCENE] --headless [--frames N | --seconds S] [--log FILE.jsonl]`: renders continuously
// offscreen while watching the shaders; one JSON line per reload.
int runWatchCommand(const std::vector<std::string>& args);

}  // namespace wb::app
