// Acceleration structures: one BLAS per mesh (a geometry per primitive), one TLAS over instances.
#pragma once
#include <vector>
#include <glm/glm.hpp>

#include "vk/resources.h"

namespace wb::vk {

struct BlasGeometry {
  VkDeviceAddress vertexAddress = 0;  // position at offset 0 of each vertex
  uint32_t vertexStride = 0;
  uint32_t vertexCount = 0;
  VkDeviceAddress indexAddress = 0;  // uint32 indices
  uint32_t triangleCount = 0;
  bool opaque = true;  // opaque geometries never run any-hit
};

struct AccelerationStructure {
  VkAccelerationStructureKHR handle = VK_NULL_HANDLE;
  Buffer buffer;
  VkDeviceAddress address = 0;
};

struct TlasInstance {
  uint32_t blas = 0;          // index into the BLAS list
  glm::mat4 transform{1.0f};  // object to world
  uint32_t customIndex = 0;   // gl_InstanceCustomIndexEXT (first GeometryInfo of its mesh)
  uint8_t mask = 0xFF;
};

class AccelerationStructures {
 public:
  AccelerationStructures() = default;
  AccelerationStructures(Context& ctx, const std::vector<std::vector<BlasGeometry>>& meshes,
                         const std::vector<TlasInstance>& instances);
  ~AccelerationStructures() { reset(); }
  AccelerationStructures(AccelerationStructures&&) = delete;
  AccelerationStructures& operator=(AccelerationStructures&&) = delete;

  void reset();
  VkAccelerationStructureKHR tlas() const { return tlas_.handle; }
  double blasBuildMs() const { return blasMs_; }
  double tlasBuildMs() const { return tlasMs_; }
  uint64_t memoryBytes() const;

 private:
  Context* ctx_ = nullptr;
  std::vector<AccelerationStructure> blas_;
  AccelerationStructure tlas_;
  Buffer instanceBuffer_;
  double blasMs_ = 0, tlasMs_ = 0;
};

}  // namespace wb::vk
