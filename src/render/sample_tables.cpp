#include "render/sample_tables.h"

namespace wb::render {

// Placeholder until the sampling library lands: the shaders do not read these yet.
std::vector<uint32_t> sobolTable() {
  return std::vector<uint32_t>(32, 0u);
}
std::vector<uint32_t> blueNoiseTable() {
  return std::vector<uint32_t>(128 * 128, 0u);
}

}  // namespace wb::render
