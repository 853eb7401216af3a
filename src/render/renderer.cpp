#include "render/renderer.h"

#include <chrono>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

namespace wb::render {

CameraState cameraFromScene(const scene::Camera& camera) {
  CameraState c;
  c.view = glm::lookAt(camera.eye, camera.target, camera.up);
  c.yfov = camera.yfov;
  c.znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  return c;
}

std::vector<float> readFloatImage(const vk::Image& image) {
  const auto bytes = image.download(VK_IMAGE_LAYOUT_GENERAL);
  std::vector<float> out(bytes.size() / sizeof(float));
  std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

eval::ImageRGBA Renderer::readImage() const {
  eval::ImageRGBA img;
  img.width = settings().width;
  img.height = settings().height;
  img.pixels = readFloatImage(outputImage());
  for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
}

std::vector<double> Renderer::render(uint32_t samples, const Progress& progress) {
  std::vector<double> seconds;
  auto& ctx = context();
  const auto start = std::chrono::steady_clock::now();
  for (uint32_t i = 0; i < samples;) {
    const auto t0 = std::chrono::steady_clock::now();
    uint32_t n = 0;
    ctx.submitAndWait([&](VkCommandBuffer cmd) { n = recordBatch(cmd, samples - i); });
    const auto t1 = std::chrono::steady_clock::now();
    // The batch's pass times, per sample (a scope of a launch of several samples divides by them).
    if (vk::GpuTimer* timer = passTimer()) timer->collect();
    seconds.insert(seconds.end(), n, std::chrono::duration<double>(t1 - t0).count() / n);
    i += n;
    if (progress && !progress(i, std::chrono::duration<double>(t1 - start).count())) break;
  }
  return seconds;
}

uint32_t Renderer::pipelineInstalls() const {
  uint32_t n = 0;
  for (const Pass* p : passes()) n += p->installs();
  return n;
}

}  // namespace wb::render
