#include "eval/image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <stb/stb_image_write.h>
#include <tinyexr.h>

namespace wb::eval {

const char* tonemapName(Tonemap t) {
  switch (t) {
    case Tonemap::Clamp:
      return "clamp";
    case Tonemap::Reinhard:
      return "reinhard";
    case Tonemap::Aces:
      return "aces";
  }
  return "?";
}

float linearToSrgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// The largest value the curves see: ACES squares its input, so anything above ~1e19 would overflow to inf
// (inf / inf = NaN -> black); every curve is 1 (white) long before this.
constexpr float kTonemapInputMax = 1e15f;

static float applyTonemap(float v, Tonemap op) {
  if (std::isnan(v)) return 0.0f;
  v = std::clamp(v, 0.0f, kTonemapInputMax);  // +inf and huge values are white, -inf black
  switch (op) {
    case Tonemap::Clamp:
      return std::min(v, 1.0f);
    case Tonemap::Reinhard:
      return v / (1.0f + v);
    case Tonemap::Aces: {
      // Narkowicz 2015 fit of the ACES filmic curve.
      const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
      return std::clamp((v * (a * v + b)) / (v * (c * v + d) + e), 0.0f, 1.0f);
    }
  }
  return v;
}

std::vector<uint8_t> tonemapToSrgb8(const ImageRGBA& image, float exposureStops, Tonemap op) {
  const float scale = std::exp2(exposureStops);
  std::vector<uint8_t> out(size_t(image.width) * image.height * 4);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = linearToSrgb(applyTonemap(image.pixels[4 * i + c] * scale, op));
      out[4 * i + c] = static_cast<uint8_t>(std::lround(v * 255.0f));
    }
    out[4 * i + 3] = 255;
  }
  return out;
}

void writePng8(const std::filesystem::path& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba8) {
  if (!stbi_write_png(path.c_str(), int(width), int(height), 4, rgba8.data(), int(width * 4))) {
    throw std::runtime_error("cannot write PNG '" + path.string() + "'");
  }
}

void writePng(const std::filesystem::path& path, const ImageRGBA& image, float exposureStops, Tonemap op) {
  writePng8(path, image.width, image.height, tonemapToSrgb8(image, exposureStops, op));
}

void writeExr(const std::filesystem::path& path, const ImageRGBA& image) {
  const char* err = nullptr;
  // tinyexr's SaveEXR takes RGBA float data (components = 4) and writes FLOAT channels when save_as_fp16 = 0.
  int rc = SaveEXR(image.pixels.data(), int(image.width), int(image.height), 4, 0, path.c_str(), &err);
  if (rc != TINYEXR_SUCCESS) {
    std::string msg = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw std::runtime_error("cannot write EXR '" + path.string() + "': " + msg);
  }
}

ImageRGBA readExr(const std::filesystem::path& path) {
  float* data = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  int rc = LoadEXR(&data, &w, &h, path.c_str(), &err);
  if (rc != TINYEXR_SUCCESS) {
    std::string msg = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw std::runtime_error("cannot read EXR '" + path.string() + "': " + msg);
  }
  ImageRGBA img;
  img.width = uint32_t(w);
  img.height = uint32_t(h);
  img.pixels.assign(data, data + size_t(w) * h * 4);
  free(data);
  return img;
}

void writeImage(const std::filesystem::path& path, const ImageRGBA& image, float exposureStops, Tonemap op) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext == ".png") return writePng(path, image, exposureStops, op);
  if (ext == ".exr") return writeExr(path, image);
  throw std::runtime_error("unsupported image format '" + ext + "' for '" + path.string() +
                           "' (use .png or .exr)");
}

}  // namespace wb::eval
