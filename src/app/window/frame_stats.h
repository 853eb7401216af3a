// A ring of recent frame times for the Stats panel's plot and the --stats JSON.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace wb::app {

class FrameStats {
 public:
  static constexpr size_t kCapacity = 240;
  void add(float ms) {
    ring_[next_] = ms;
    next_ = (next_ + 1) % kCapacity;
    count_ = std::min(count_ + 1, kCapacity);
    last_ = ms;
  }
  size_t count() const { return count_; }
  float last() const { return last_; }
  // Oldest first.
  std::vector<float> values() const {
    std::vector<float> v;
    v.reserve(count_);
    for (size_t i = 0; i < count_; ++i) v.push_back(ring_[(next_ + kCapacity - count_ + i) % kCapacity]);
    return v;
  }
  float mean() const {
    float s = 0;
    for (float v : values()) s += v;
    return count_ ? s / float(count_) : 0.0f;
  }
  float percentile(float p) const {
    auto v = values();
    if (v.empty()) return 0.0f;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(p * float(v.size() - 1) + 0.5f))];
  }
  float max() const {
    auto v = values();
    return v.empty() ? 0.0f : *std::max_element(v.begin(), v.end());
  }

 private:
  std::array<float, kCapacity> ring_{};
  size_t next_ = 0, count_ = 0;
  float last_ = 0;
};

}  // namespace wb::app
