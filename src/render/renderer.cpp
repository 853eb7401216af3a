#include "render/renderer.h"

#include <chrono>
#include <glm/gtc/matrix_transform.hpp>

namespace wb::render {

CameraState cameraFromScene(const scene::Camera& camera) {
  CameraState c;
  c.view = glm::lookAt(camera.eye, camera.target, camera.up);
  c.yfov = camera.yfov;
  c.znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  return c;
}

std::vector<double> Renderer::render(uint32_t samples) {
  std::vector<double> seconds;
  auto& ctx = context();
  for (uint32_t i = 0; i < samples; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    ctx.submitAndWait([&](VkCommandBuffer cmd) { record(cmd); });
    advance();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return seconds;
}

}  // namespace wb::render
