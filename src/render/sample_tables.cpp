#include "render/sample_tables.h"

#include "sampling/blue_noise.h"
#include "sampling/sobol.h"
#include "shared/random.h"

namespace wb::render {

std::vector<uint32_t> sobolTable() {
  return sobolDirectionNumbers(int(WB_SOBOL_DIMS));
}
std::vector<uint32_t> blueNoiseTable() {
  return blueNoise128();
}

}  // namespace wb::render
