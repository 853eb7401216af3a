#pragma once
#include <string>
#include <vector>

namespace wb::app {

// `workbench render [SCENE] --size WxH --spp N --out FILE.png|FILE.exr [--stats FILE.json] ...`
int runRenderCommand(const std::vector<std::string>& args);

}  // namespace wb::app
