// Stand-alone driver of the `shaders` command (for manual runs before it is wired into build/workbench).
#include "app/cmd_shaders.h"

int main(int argc, char** argv) {
  return wb::runShadersCommand(std::vector<std::string>(argv + 1, argv + argc));
}
