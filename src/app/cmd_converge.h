#pragma once
#include <string>
#include <vector>

namespace wb::app {

// `workbench converge [SCENE] (--reference REF.exr | --reference-spp N) [--seconds S] [--runs R]
//  [--config NAME:FLAGS]... --out DIR [render flags]`: progressive renders of each configuration with
// error-against-reference checkpoints; writes converge.csv, converge.png (gnuplot), converge.md and error
// images to DIR. `--hard-cases` renders the built-in numerical hard-case scenes instead and writes
// hard_cases.md.
int runConvergeCommand(const std::vector<std::string>& args);

}  // namespace wb::app
