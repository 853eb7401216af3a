// IEEE 754 half-precision (binary16) to float, for reading back the 16-bit float images (AOVs, reflections).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace wb {

// Exact: every half is a float. Subnormals, infinities and NaNs included.
inline float halfToFloat(uint16_t h) {
  const uint32_t sign = (h >> 15) & 1u, exp = (h >> 10) & 0x1Fu, mant = h & 0x3FFu;
  float v;
  if (exp == 0) {
    v = std::ldexp(float(mant), -24);
  } else if (exp == 31) {
    v = mant ? NAN : INFINITY;
  } else {
    v = std::ldexp(float(mant | 0x400u), int(exp) - 25);
  }
  return sign ? -v : v;
}

// Native-endian halves, two bytes each (a trailing odd byte is ignored).
inline std::vector<float> halvesToFloats(const std::vector<uint8_t>& bytes) {
  std::vector<float> out(bytes.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) {
    uint16_t h;
    std::memcpy(&h, bytes.data() + 2 * i, 2);
    out[i] = halfToFloat(h);
  }
  return out;
}

}  // namespace wb
