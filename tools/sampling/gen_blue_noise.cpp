// Regenerates assets/sampling/blue_noise_128.bin (two 128x128 void-and-cluster masks, packed 16+16 bits,
// little endian). Usage: wb_gen_blue_noise [output path]   (default:
// <project>/assets/sampling/blue_noise_128.bin)
#include <cstdio>
#include <fstream>
#include <iostream>

#include "sampling/blue_noise.h"

int main(int argc, char** argv) {
  std::filesystem::path out = argc > 1 ? std::filesystem::path(argv[1]) : wb::blueNoise128Path();
  std::vector<uint32_t> tex = wb::generateBlueNoise128();
  std::filesystem::create_directories(out.parent_path());
  std::ofstream f(out, std::ios::binary);
  for (uint32_t v : tex) {
    const char bytes[4] = {static_cast<char>(v & 0xffu), static_cast<char>((v >> 8) & 0xffu),
                           static_cast<char>((v >> 16) & 0xffu), static_cast<char>((v >> 24) & 0xffu)};
    f.write(bytes, 4);
  }
  if (!f) {
    std::cerr << "cannot write " << out << "\n";
    return 1;
  }
  std::cout << "wrote " << out << " (" << tex.size() << " texels)\n";
  return 0;
}
