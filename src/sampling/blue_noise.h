// Blue noise: a void-and-cluster generator (Ulichney 1993) and the committed 128x128 two-channel texture.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace wb {

// Void-and-cluster dither array of size x size (power of two not required): a permutation of 0..size^2-1
// (row-major, [y * size + x]). Gaussian energy filter (sigma 1.5) on the torus; deterministic for a seed.
std::vector<uint32_t> voidAndCluster(int size, uint32_t seed, float sigma = 1.5f);

// The 128x128 texture packed as WB_BIND_BLUE_NOISE expects: bits 0-15 channel 0, bits 16-31 channel 1, each
// rank * 4 (rank 0..16383 of two independent void-and-cluster masks), so wbUnpackBlueNoise gives rank /
// 16384.
std::vector<uint32_t> generateBlueNoise128();

// Path of the committed texture: assetDir()/sampling/blue_noise_128.bin (16384 little-endian uint32).
std::filesystem::path blueNoise128Path();

// Loads the committed texture (throws std::runtime_error if it is missing or malformed).
std::vector<uint32_t> blueNoise128();

}  // namespace wb
