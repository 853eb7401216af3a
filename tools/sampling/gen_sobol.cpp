// Regenerates assets/sampling/sobol_dirs.bin: the Sobol direction numbers of src/sampling/sobol.cpp's search
// for kSobolCommittedDims dimensions, [dim * 32 + bit], little-endian uint32. Usage: wb_gen_sobol [output
// path] (default: <project>/assets/sampling/sobol_dirs.bin). The test Sobol.CommittedTableMatchesGenerator
// fails when the committed file and the search disagree.
#include <cstdio>
#include <fstream>
#include <iostream>

#include "sampling/sobol.h"

int main(int argc, char** argv) {
  std::filesystem::path out = argc > 1 ? std::filesystem::path(argv[1]) : wb::sobolCommittedPath();
  const std::vector<uint32_t> dirs = wb::generateSobolDirectionNumbers(wb::kSobolCommittedDims);
  if (!out.parent_path().empty()) std::filesystem::create_directories(out.parent_path());
  std::ofstream f(out, std::ios::binary);
  for (uint32_t v : dirs) {
    const char bytes[4] = {static_cast<char>(v & 0xffu), static_cast<char>((v >> 8) & 0xffu),
                           static_cast<char>((v >> 16) & 0xffu), static_cast<char>((v >> 24) & 0xffu)};
    f.write(bytes, 4);
  }
  if (!f) {
    std::cerr << "cannot write " << out << "\n";
    return 1;
  }
  std::cout << "wrote " << out << " (" << wb::kSobolCommittedDims << " dimensions)\n";
  return 0;
}
