#include "vk/accel.h"

#include <chrono>
#include <cstring>

namespace wb::vk {
namespace {

AccelerationStructure createAs(Context& ctx, VkAccelerationStructureTypeKHR type, VkDeviceSize size) {
  AccelerationStructure as;
  as.buffer = Buffer(ctx, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, false);
  VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  ci.buffer = as.buffer.handle();
  ci.size = size;
  ci.type = type;
  WB_VK(ctx.vkCreateAccelerationStructureKHR(ctx.device(), &ci, nullptr, &as.handle));
  VkAccelerationStructureDeviceAddressInfoKHR ai{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  ai.accelerationStructure = as.handle;
  as.address = ctx.vkGetAccelerationStructureDeviceAddressKHR(ctx.device(), &ai);
  return as;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

AccelerationStructures::AccelerationStructures(Context& ctx,
                                               const std::vector<std::vector<BlasGeometry>>& meshes,
                                               const std::vector<TlasInstance>& instances)
    : ctx_(&ctx) {
  const VkDeviceSize scratchAlign = std::max<uint32_t>(ctx.rayTracing().minScratchAlignment, 1);
  auto t0 = std::chrono::steady_clock::now();

  // Bottom level: one build per mesh, all recorded into one submission with a shared scratch buffer region
  // each.
  struct Pending {
    std::vector<VkAccelerationStructureGeometryKHR> geometries;
    std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges;
    VkAccelerationStructureBuildGeometryInfoKHR info{};
    VkDeviceSize scratchOffset = 0;
  };
  std::vector<Pending> pending(meshes.size());
  VkDeviceSize scratchTotal = 0;
  for (size_t m = 0; m < meshes.size(); ++m) {
    Pending& p = pending[m];
    std::vector<uint32_t> counts;
    for (const auto& g : meshes[m]) {
      VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
      geom.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
      geom.flags =
          g.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR;
      auto& tri = geom.geometry.triangles;
      tri.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
      tri.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
      tri.vertexData.deviceAddress = g.vertexAddress;
      tri.vertexStride = g.vertexStride;
      tri.maxVertex = g.vertexCount ? g.vertexCount - 1 : 0;
      tri.indexType = VK_INDEX_TYPE_UINT32;
      tri.indexData.deviceAddress = g.indexAddress;
      p.geometries.push_back(geom);
      p.ranges.push_back({g.triangleCount, 0, 0, 0});
      counts.push_back(g.triangleCount);
    }
    p.info.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR;
    p.info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
    p.info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    p.info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    p.info.geometryCount = static_cast<uint32_t>(p.geometries.size());
    p.info.pGeometries = p.geometries.data();
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    ctx.vkGetAccelerationStructureBuildSizesKHR(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                                &p.info, counts.data(), &sizes);
    blas_.push_back(
        createAs(ctx, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, sizes.accelerationStructureSize));
    p.info.dstAccelerationStructure = blas_.back().handle;
    p.scratchOffset = scratchTotal;
    scratchTotal = alignUp(scratchTotal + sizes.buildScratchSize, scratchAlign);
  }
  if (!meshes.empty()) {
    Buffer scratch(ctx, scratchTotal + scratchAlign, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    const VkDeviceAddress scratchBase = alignUp(scratch.address(), scratchAlign);
    std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePtrs;
    std::vector<VkAccelerationStructureBuildGeometryInfoKHR> infos;
    for (auto& p : pending) {
      p.info.scratchData.deviceAddress = scratchBase + p.scratchOffset;
      infos.push_back(p.info);
      rangePtrs.push_back(p.ranges.data());
    }
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      ctx.vkCmdBuildAccelerationStructuresKHR(cmd, static_cast<uint32_t>(infos.size()), infos.data(),
                                              rangePtrs.data());
    });
  }
  blasMs_ = msSince(t0);

  // Top level.
  t0 = std::chrono::steady_clock::now();
  std::vector<VkAccelerationStructureInstanceKHR> vkInstances;
  for (const auto& inst : instances) {
    VkAccelerationStructureInstanceKHR vi{};
    const glm::mat4& m = inst.transform;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) vi.transform.matrix[r][c] = m[c][r];
    }
    vi.instanceCustomIndex = inst.customIndex & 0xFFFFFF;
    vi.mask = inst.mask;
    vi.instanceShaderBindingTableRecordOffset = 0;
    vi.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    vi.accelerationStructureReference = blas_.at(inst.blas).address;
    vkInstances.push_back(vi);
  }
  instanceBuffer_ = Buffer(
      ctx, std::max<size_t>(vkInstances.size(), 1) * sizeof(VkAccelerationStructureInstanceKHR),
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
      false);
  if (!vkInstances.empty()) instanceBuffer_.upload(vkInstances);

  VkAccelerationStructureGeometryKHR geom{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geom.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  geom.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  geom.geometry.instances.data.deviceAddress = instanceBuffer_.address();
  VkAccelerationStructureBuildGeometryInfoKHR info{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  info.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  info.geometryCount = 1;
  info.pGeometries = &geom;
  uint32_t count = static_cast<uint32_t>(vkInstances.size());
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  ctx.vkGetAccelerationStructureBuildSizesKHR(ctx.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                              &info, &count, &sizes);
  tlas_ = createAs(ctx, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, sizes.accelerationStructureSize);
  Buffer scratch(ctx, sizes.buildScratchSize + scratchAlign, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  info.dstAccelerationStructure = tlas_.handle;
  info.scratchData.deviceAddress = alignUp(scratch.address(), scratchAlign);
  VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* rangePtr = &range;
  ctx.submitAndWait(
      [&](VkCommandBuffer cmd) { ctx.vkCmdBuildAccelerationStructuresKHR(cmd, 1, &info, &rangePtr); });
  tlasMs_ = msSince(t0);
}

void AccelerationStructures::reset() {
  if (!ctx_) return;
  for (auto& b : blas_) ctx_->vkDestroyAccelerationStructureKHR(ctx_->device(), b.handle, nullptr);
  if (tlas_.handle) ctx_->vkDestroyAccelerationStructureKHR(ctx_->device(), tlas_.handle, nullptr);
  blas_.clear();
  tlas_ = {};
  ctx_ = nullptr;
}

uint64_t AccelerationStructures::memoryBytes() const {
  uint64_t total = tlas_.buffer.size() + instanceBuffer_.size();
  for (const auto& b : blas_) total += b.buffer.size();
  return total;
}

}  // namespace wb::vk
