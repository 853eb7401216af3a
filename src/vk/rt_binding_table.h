// A ray tracing program's shader groups, named by their stages' file names, in shader binding table order:
// one raygen group, the miss groups (in the order traceRayEXT's miss index counts them), then the hit groups
// (in the order the SBT offset counts them). The pipeline resolves the names against a program build's
// stages.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "shader/types.h"

namespace wb::vk {

struct RtHitGroup {
  std::string closestHit;    // e.g. "closesthit.rchit"; empty: none (occlusion-only groups)
  std::string anyHit;        // optional: a program may leave it out (e.g. when every material is opaque)
  std::string intersection;  // optional, as anyHit; empty: triangles
};

// A group as Vulkan takes it: stage indices into the program's stage list, -1 where unused.
struct RtShaderGroup {
  int general = -1;  // raygen, miss or callable
  int closestHit = -1;
  int anyHit = -1;
  int intersection = -1;
};

class RtBindingTable {
 public:
  RtBindingTable& raygen(std::string stage);
  RtBindingTable& miss(std::string stage);  // the same stage may serve several miss indices
  RtBindingTable& hitGroup(RtHitGroup group);

  uint32_t missCount() const { return static_cast<uint32_t>(miss_.size()); }
  uint32_t hitCount() const { return static_cast<uint32_t>(hit_.size()); }

  // The groups in SBT order, indexing `stages`. Throws std::invalid_argument naming what is missing when the
  // raygen, a miss or a closest-hit stage is not among them.
  std::vector<RtShaderGroup> resolve(
      const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages) const;

 private:
  std::string raygen_;
  std::vector<std::string> miss_;
  std::vector<RtHitGroup> hit_;
};

}  // namespace wb::vk
