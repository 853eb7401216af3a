#include "vk/rt_binding_table.h"

#include <stdexcept>

namespace wb::vk {
namespace {

int find(const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages, const std::string& name,
         bool required, const char* role) {
  if (name.empty()) return -1;
  for (size_t i = 0; i < stages.size(); ++i)
    if (stages[i]->key.path.filename() == name) return static_cast<int>(i);
  if (required)
    throw std::invalid_argument(std::string("ray tracing program has no ") + role + " stage '" + name + "'");
  return -1;
}

}  // namespace

RtBindingTable& RtBindingTable::raygen(std::string stage) {
  raygen_ = std::move(stage);
  return *this;
}

RtBindingTable& RtBindingTable::miss(std::string stage) {
  miss_.push_back(std::move(stage));
  return *this;
}

RtBindingTable& RtBindingTable::hitGroup(RtHitGroup group) {
  hit_.push_back(std::move(group));
  return *this;
}

std::vector<RtShaderGroup> RtBindingTable::resolve(
    const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages) const {
  std::vector<RtShaderGroup> groups;
  groups.push_back({find(stages, raygen_, true, "raygen")});
  for (const auto& m : miss_) groups.push_back({find(stages, m, true, "miss")});
  for (const auto& h : hit_) {
    groups.push_back({-1, find(stages, h.closestHit, true, "closest-hit"),
                      find(stages, h.anyHit, false, "any-hit"),
                      find(stages, h.intersection, false, "intersection")});
  }
  return groups;
}

}  // namespace wb::vk
