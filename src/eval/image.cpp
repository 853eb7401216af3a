#include "eval/image.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <stb/stb_image_write.h>
#include <tinyexr.h>

#include "common/atomic_file.h"
#include "common/file_io.h"

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

std::string encodePng8(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, int(width), int(height), 4, rgba8.data(), int(width * 4)))
    throw std::runtime_error("cannot encode a " + std::to_string(width) + "x" + std::to_string(height) +
                             " PNG");
  return png;
}

void writePng8(const std::filesystem::path& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba8) {
  writeFileAtomically(path, encodePng8(width, height, rgba8), "");
}

void writePng(const std::filesystem::path& path, const ImageRGBA& image, float exposureStops, Tonemap op) {
  writePng8(path, image.width, image.height, tonemapToSrgb8(image, exposureStops, op));
}

std::string encodeExr(const ImageRGBA& image) {
  // Linear float RGBA, stored as EXR viewers expect it: channels A, B, G, R, uncompressed for tiny images and
  // ZIP otherwise (as tinyexr's SaveEXR writes files).
  const size_t n = size_t(image.width) * image.height;
  std::vector<float> planes[4];
  for (auto& p : planes) p.resize(n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) planes[3 - c][i] = image.pixels[4 * i + size_t(c)];
  float* planePointers[4] = {planes[0].data(), planes[1].data(), planes[2].data(), planes[3].data()};
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = 4;
  exr.images = reinterpret_cast<unsigned char**>(planePointers);
  exr.width = int(image.width);
  exr.height = int(image.height);
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type =
      image.width < 16 && image.height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
  EXRChannelInfo channels[4] = {};
  const char* names[4] = {"A", "B", "G", "R"};
  for (int c = 0; c < 4; ++c) channels[c].name[0] = names[c][0];
  int pixelTypes[4] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT,
                       TINYEXR_PIXELTYPE_FLOAT};
  header.num_channels = 4;
  header.channels = channels;
  header.pixel_types = pixelTypes;
  header.requested_pixel_types = pixelTypes;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err);
  if (size == 0 || !memory) {
    std::string msg = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    free(memory);
    throw std::runtime_error("cannot encode an EXR image: " + msg);
  }
  std::string out(reinterpret_cast<const char*>(memory), size);
  free(memory);
  return out;
}

void writeExr(const std::filesystem::path& path, const ImageRGBA& image) {
  writeFileAtomically(path, encodeExr(image), "");
}

ImageRGBA readExr(const std::filesystem::path& path) {
  auto fail = [&](const std::string& why) {
    return std::runtime_error("cannot read EXR '" + path.string() + "': " + why);
  };
  std::string why;
  const auto data = readRegularFile(path, &why);  // never blocks on a named pipe
  if (!data) {
    const std::string kind = describeFileKind(path);
    throw fail(kind == "missing" ? "no such file" : why);
  }
  static const unsigned char kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  if (data->size() < 4 || std::memcmp(data->data(), kExrMagic, 4) != 0) {
    static const unsigned char kPngMagic[4] = {0x89, 'P', 'N', 'G'};
    const bool png = data->size() >= 4 && std::memcmp(data->data(), kPngMagic, 4) == 0;
    throw fail(
        png ? "a PNG image, not OpenEXR (a reference is linear radiance: render it with --out FILE.exr)"
            : "not an OpenEXR image (no EXR signature)");
  }
  float* pixels = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  const int rc = LoadEXRFromMemory(&pixels, &w, &h, reinterpret_cast<const unsigned char*>(data->data()),
                                   data->size(), &err);
  if (rc != TINYEXR_SUCCESS) {
    std::string msg = err ? err : "tinyexr error " + std::to_string(rc);
    if (err) FreeEXRErrorMessage(err);
    throw fail(msg);
  }
  ImageRGBA img;
  img.width = uint32_t(w);
  img.height = uint32_t(h);
  img.pixels.assign(pixels, pixels + size_t(w) * h * 4);
  free(pixels);
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
