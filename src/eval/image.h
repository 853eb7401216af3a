// Linear float RGB(A) images on the host: tonemapping, PNG (for viewing) and EXR (linear) files.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wb::eval {

struct ImageRGBA {
  uint32_t width = 0, height = 0;
  std::vector<float> pixels;  // width * height * 4, row 0 at the top, linear scene-referred radiance
  float at(uint32_t x, uint32_t y, int c) const { return pixels[(size_t(y) * width + x) * 4 + c]; }
};

enum class Tonemap { Clamp, Reinhard, Aces };
const char* tonemapName(Tonemap t);

// Linear radiance -> display sRGB 8-bit (exposure in stops).
std::vector<uint8_t> tonemapToSrgb8(const ImageRGBA& image, float exposureStops = 0.0f,
                                    Tonemap op = Tonemap::Aces);
float linearToSrgb(float v);

// PNG is tonemapped for viewing; EXR keeps linear float RGBA. Each file is written whole or not at all
// (common/atomic_file.h); a failure throws std::runtime_error naming the path and what failed (a full disk,
// a permission).
void writePng(const std::filesystem::path& path, const ImageRGBA& image, float exposureStops = 0.0f,
              Tonemap op = Tonemap::Aces);
void writePng8(const std::filesystem::path& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba8);
void writeExr(const std::filesystem::path& path, const ImageRGBA& image);
// The file's bytes, for writers that put an image somewhere else first.
std::string encodePng8(uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8);
std::string encodeExr(const ImageRGBA& image);
// Reads a regular file only (a named pipe is refused, not waited on); says "no such file", "a PNG image, not
// OpenEXR" and the like in its std::runtime_error, with the path.
ImageRGBA readExr(const std::filesystem::path& path);
// Writes PNG or EXR by the file extension (.png / .exr); anything else is an error.
void writeImage(const std::filesystem::path& path, const ImageRGBA& image, float exposureStops = 0.0f,
                Tonemap op = Tonemap::Aces);

}  // namespace wb::eval
