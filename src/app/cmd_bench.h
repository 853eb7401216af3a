#pragma once
#include <string>
#include <vector>

namespace wb::app {

// `workbench bench [--quick] [--out FILE.json]`: the performance suite (path tracer rates per scene,
// specialised vs generic; acceleration-structure builds; memory; cold/warm start-up; hot-reload latency). Not
// a test.
int runBenchCommand(const std::vector<std::string>& args);

}  // namespace wb::app
