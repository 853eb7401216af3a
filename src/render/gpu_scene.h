// A scene on the device: vertex/index buffers, per-geometry records, materials, textures, and the
// acceleration structures over them. Built once per loaded scene; the passes only read it. The directional
// lights are each renderer's (the sun's size is a render setting).
#pragma once
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "vk/accel.h"
#include "vk/resources.h"

namespace wb::render {

class GpuScene {
 public:
  GpuScene(vk::Context& ctx, const scene::Scene& scene);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  VkAccelerationStructureKHR tlas() const { return accel_->tlas(); }
  const vk::Buffer& geometries() const { return geometries_; }
  const vk::Buffer& materials() const { return materials_; }
  uint32_t lightCount() const { return lightCount_; }  // the scene's directional lights (fixed at load)
  // Emissive triangles (area lights) and the alias table that picks one proportionally to its power.
  const vk::Buffer& emitters() const { return emitters_; }
  const vk::Buffer& emitterAlias() const { return emitterAlias_; }
  uint32_t emitterCount() const { return emitterCount_; }
  float emitterTotalPower() const { return emitterTotalPower_; }
  // Glossy reflectors (scene/reflectors.h) as bounding spheres (vec4: centre, radius), and how many the path
  // tracer guides towards: none in a scene without lights (directional or area), where no sharp highlight
  // forms.
  const vk::Buffer& reflectors() const { return reflectors_; }
  uint32_t reflectorCount() const { return lightCount_ > 0 || emitterCount_ > 0 ? reflectorCount_ : 0; }
  // Changes whenever the emitter (and reflector) buffers are rebuilt (a material edit): passes rewrite their
  // descriptors.
  uint64_t emitterVersion() const { return emitterVersion_; }
  // One entry per scene texture (a 1x1 white image where a texture has no usable image).
  const std::vector<VkDescriptorImageInfo>& textureDescriptors() const { return textureInfos_; }
  const vk::AccelerationStructures& accel() const { return *accel_; }
  uint64_t deviceBytes() const;
  bool anyNonOpaque() const { return anyNonOpaque_; }

  // Material factors can be edited live; this rewrites the material buffer and rebuilds the area lights'
  // table (an edited emission changes what next-event estimation samples; MIS needs the two to agree). Call
  // it at a frame boundary: it waits for the device.
  void updateMaterials(const std::vector<gpu::Material>& materials);

 private:
  void buildEmitters(const std::vector<gpu::Material>& materials);

  vk::Context& ctx_;
  const scene::Scene& source_;
  uint64_t emitterVersion_ = 0;
  std::vector<vk::Buffer> vertexBuffers_, indexBuffers_;
  vk::Buffer geometries_, materials_, emitters_, emitterAlias_, reflectors_;
  uint32_t reflectorCount_ = 0;
  uint32_t emitterCount_ = 0;
  float emitterTotalPower_ = 0.0f;
  uint32_t lightCount_ = 0;
  std::vector<vk::Image> images_;
  std::vector<VkSampler> samplers_;
  std::vector<VkDescriptorImageInfo> textureInfos_;
  std::unique_ptr<vk::AccelerationStructures> accel_;
  bool anyNonOpaque_ = false;
};

class Pass;
class GpuEnvironment;
// Sets the scene's and the environment's resources on `pass` under the names the shaders declare them
// (shaders/shared/scene.glsl and the path tracer's lights, environment sampling and emitters).
void bindSceneResources(Pass& pass, const GpuScene& scene, const GpuEnvironment& env);

}  // namespace wb::render
