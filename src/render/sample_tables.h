// Tables the path tracer's sampler reads on the device: Sobol direction numbers and the blue-noise texture.
#pragma once
#include <cstdint>
#include <vector>

namespace wb::render {

std::vector<uint32_t> sobolTable();      // [dim * 32 + bit]
std::vector<uint32_t> blueNoiseTable();  // 128 x 128, two 16-bit channels per texel

}  // namespace wb::render
