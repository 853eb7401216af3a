#include "sampling/blue_noise.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "common/paths.h"

namespace wb {
namespace {

constexpr uint32_t kSeedChannel0 = 0x5eed0001u;
constexpr uint32_t kSeedChannel1 = 0x5eed0002u;

uint32_t hash32(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Energy field of a binary pattern under a toroidal Gaussian filter, updated incrementally.
class EnergyField {
 public:
  EnergyField(int size, float sigma) : size_(size), energy_(static_cast<size_t>(size) * size, 0.0) {
    radius_ = std::min(size / 2, static_cast<int>(std::ceil(4.0f * sigma)));
    int w = 2 * radius_ + 1;
    kernel_.resize(static_cast<size_t>(w) * w);
    for (int dy = -radius_; dy <= radius_; ++dy) {
      for (int dx = -radius_; dx <= radius_; ++dx) {
        kernel_[static_cast<size_t>(dy + radius_) * w + (dx + radius_)] =
            std::exp(-static_cast<double>(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      }
    }
  }
  void add(int idx, double sign) {
    int x0 = idx % size_;
    int y0 = idx / size_;
    int w = 2 * radius_ + 1;
    for (int dy = -radius_; dy <= radius_; ++dy) {
      int y = ((y0 + dy) % size_ + size_) % size_;
      for (int dx = -radius_; dx <= radius_; ++dx) {
        int x = ((x0 + dx) % size_ + size_) % size_;
        energy_[static_cast<size_t>(y) * size_ + x] +=
            sign * kernel_[static_cast<size_t>(dy + radius_) * w + (dx + radius_)];
      }
    }
  }
  // Tightest cluster: the set pixel with the highest energy. Largest void: the empty pixel with the lowest.
  int tightestCluster(const std::vector<uint8_t>& bits) const {
    int best = -1;
    for (size_t i = 0; i < bits.size(); ++i) {
      if (bits[i] && (best < 0 || energy_[i] > energy_[best])) best = static_cast<int>(i);
    }
    return best;
  }
  int largestVoid(const std::vector<uint8_t>& bits) const {
    int best = -1;
    for (size_t i = 0; i < bits.size(); ++i) {
      if (!bits[i] && (best < 0 || energy_[i] < energy_[best])) best = static_cast<int>(i);
    }
    return best;
  }

 private:
  int size_;
  int radius_;
  std::vector<double> kernel_;
  std::vector<double> energy_;
};

}  // namespace

std::vector<uint32_t> voidAndCluster(int size, uint32_t seed, float sigma) {
  if (size < 4) throw std::invalid_argument("voidAndCluster: size must be >= 4");
  const int n = size * size;
  // Initial binary pattern: ~10% random pixels (deterministic from the seed).
  std::vector<uint8_t> bits(n, 0);
  int ones = std::max(1, n / 10);
  {
    uint32_t state = hash32(seed);
    int placed = 0;
    while (placed < ones) {
      state = hash32(state + 0x9e3779b9u);
      int idx = static_cast<int>(state % static_cast<uint32_t>(n));
      if (!bits[idx]) {
        bits[idx] = 1;
        ++placed;
      }
    }
  }
  EnergyField field(size, sigma);
  for (int i = 0; i < n; ++i) {
    if (bits[i]) field.add(i, 1.0);
  }
  // Relax to the initial prototype: move the tightest cluster into the largest void until stable.
  for (int iter = 0; iter < 4 * n; ++iter) {
    int cluster = field.tightestCluster(bits);
    bits[cluster] = 0;
    field.add(cluster, -1.0);
    int hole = field.largestVoid(bits);
    bits[hole] = 1;
    field.add(hole, 1.0);
    if (hole == cluster) break;
  }
  std::vector<uint32_t> rank(n, 0u);
  // Phase 1: remove clusters from a copy of the prototype, ranks ones-1 .. 0.
  {
    std::vector<uint8_t> b = bits;
    EnergyField f = field;
    for (int r = ones - 1; r >= 0; --r) {
      int cluster = f.tightestCluster(b);
      b[cluster] = 0;
      f.add(cluster, -1.0);
      rank[cluster] = static_cast<uint32_t>(r);
    }
  }
  // Phases 2 and 3: fill the largest voids, ranks ones .. n-1. (On the torus the energy of the zeros is the
  // kernel sum minus the energy of the ones, so phase 3's "tightest cluster of zeros" is this same largest
  // void.)
  for (int r = ones; r < n; ++r) {
    int hole = field.largestVoid(bits);
    bits[hole] = 1;
    field.add(hole, 1.0);
    rank[hole] = static_cast<uint32_t>(r);
  }
  return rank;
}

std::vector<uint32_t> generateBlueNoise128() {
  std::vector<uint32_t> a = voidAndCluster(128, kSeedChannel0);
  std::vector<uint32_t> b = voidAndCluster(128, kSeedChannel1);
  std::vector<uint32_t> out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = (a[i] * 4u) | ((b[i] * 4u) << 16);
  return out;
}

std::filesystem::path blueNoise128Path() {
  return assetDir() / "sampling" / "blue_noise_128.bin";
}

std::vector<uint32_t> blueNoise128() {
  const std::filesystem::path path = blueNoise128Path();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("blueNoise128: cannot open " + path.string());
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() != 128u * 128u * 4u) {
    throw std::runtime_error("blueNoise128: " + path.string() + " has " + std::to_string(bytes.size()) +
                             " bytes, expected 65536");
  }
  std::vector<uint32_t> out(128u * 128u);
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<uint32_t>(bytes[4 * i]) | (static_cast<uint32_t>(bytes[4 * i + 1]) << 8) |
             (static_cast<uint32_t>(bytes[4 * i + 2]) << 16) |
             (static_cast<uint32_t>(bytes[4 * i + 3]) << 24);
  }
  return out;
}

}  // namespace wb
