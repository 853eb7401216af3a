#include "render/roofline.h"

#include <glm/gtc/matrix_transform.hpp>

#include "common/paths.h"

namespace wb::render {

const char* bareRaysName(BareRays kind) {
  switch (kind) {
    case BareRays::Primary:
      return "primary";
    case BareRays::Diffuse:
      return "diffuse";
    case BareRays::Shadow:
      return "shadow";
    default:
      return "path";
  }
}

Roofline::Roofline(const RendererResources& r, uint32_t width, uint32_t height, const CameraState& camera,
                   uint32_t bounces)
    : ctx_(r.ctx), width_(width), height_(height) {
  RayTracingRecipe recipe;
  recipe.table.raygen("roofline.rgen").miss("roofline.rmiss").hitGroup({.closestHit = "roofline.rchit"});
  pass_ = std::make_unique<Pass>(ctx_, r.library, "roofline", std::move(recipe));
  pass_->setPushConstantBytes(sizeof(gpu::RooflineConstants));
  const auto dir = shaderDir() / "roofline";
  pass_->useProgram("roofline",
                    {{dir / "roofline.rgen"}, {dir / "roofline.rmiss"}, {dir / "roofline.rchit"}});

  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  hitImage_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  normals_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  result_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* img : {&hitImage_, &normals_, &result_})
      vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
  });
  pass_->setAccelerationStructure("tlas", r.gpuScene.tlas());
  pass_->setBuffer("GeometryBlock", r.gpuScene.geometries());
  pass_->setStorageImage("rooflineHits", hitImage_.view());
  pass_->setStorageImage("rooflineNormals", normals_.view());
  pass_->setStorageImage("rooflineResult", result_.view());
  pass_->rebuild();

  // Camera rays as the path tracer's (raygen.rgen) through pixel centres: its unprojected direction is linear
  // in the pixel position before normalisation, so a corner and two steps give every pixel's.
  const float aspect = float(width) / float(height);
  glm::mat4 proj = glm::perspective(camera.yfov, aspect, camera.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const glm::mat4 viewInverse = glm::inverse(camera.view), projInverse = glm::inverse(proj);
  const auto direction = [&](float ndcX, float ndcY) {
    const glm::vec4 target = projInverse * glm::vec4(ndcX, ndcY, 1.0f, 1.0f);
    return glm::vec3(viewInverse * glm::vec4(glm::vec3(target), 0.0f));
  };
  const glm::vec3 corner = direction(-1.0f, -1.0f);
  constants_.origin = viewInverse * glm::vec4(0, 0, 0, 1);
  constants_.corner = glm::vec4(corner, 0.0f);
  constants_.dx = glm::vec4(direction(-1.0f + 2.0f / float(width), -1.0f) - corner, 0.0f);
  constants_.dy = glm::vec4(direction(-1.0f, -1.0f + 2.0f / float(height)) - corner, 0.0f);
  const glm::vec3 toLight =
      r.scene.lights.empty() ? glm::vec3(0, 1, 0) : -glm::normalize(r.scene.lights.front().direction);
  constants_.toLight = glm::vec4(toLight, 0.0f);
  constants_.imageSize = glm::uvec2(width, height);
  constants_.bounces = bounces;

  // The G-buffer, and what the other kinds trace from it.
  ctx_.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, BareRays::Primary, 1); });
  const auto hits = readHits(), normals = readFloatImage(normals_);
  for (size_t i = 0; i < hits.size(); i += 4) {
    if (!(hits[i + 3] > 0.0f)) continue;
    ++hits_;
    // The shader's test (roofline.rgen), in the same float arithmetic.
    if (normals[i] * toLight.x + normals[i + 1] * toLight.y + normals[i + 2] * toLight.z > 0.0f) ++litHits_;
  }
  ctx_.submitAndWait([&](VkCommandBuffer cmd) { record(cmd, BareRays::Path, 1); });
  const auto walks = readResult();
  for (size_t i = 0; i < walks.size(); i += 4) pathRays_ += uint64_t(walks[i]);
}

Roofline::~Roofline() {
  ctx_.waitIdle();
}

uint64_t Roofline::raysPerLaunch(BareRays kind) const {
  switch (kind) {
    case BareRays::Primary:
      return uint64_t(width_) * height_;
    case BareRays::Diffuse:
      return uint64_t(width_) * height_ + hits_;
    case BareRays::Shadow:
      return litHits_;
    default:
      return pathRays_;
  }
}

void Roofline::record(VkCommandBuffer cmd, BareRays kind, uint32_t launches) {
  pass_->bind(cmd);
  for (uint32_t i = 0; i < launches; ++i) {
    constants_.kind = kind == BareRays::Primary   ? WB_ROOFLINE_PRIMARY
                      : kind == BareRays::Diffuse ? WB_ROOFLINE_DIFFUSE
                      : kind == BareRays::Shadow  ? WB_ROOFLINE_SHADOW
                                                  : WB_ROOFLINE_PATH;
    constants_.frame = frame_++;
    pass_->push(cmd, constants_);
    pass_->traceRays(cmd, width_, height_);
    vk::memoryBarrier(cmd);
  }
}

}  // namespace wb::render
