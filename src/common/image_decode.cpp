#include "common/image_decode.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <stb/stb_image.h>

namespace wb {
namespace {

[[noreturn]] void fail(const std::string& why) {
  throw ImageDecodeError(why);
}

void checkDimensions(uint64_t width, uint64_t height, const char* format) {
  if (width == 0 || height == 0) fail(std::string(format) + " image has no pixels");
  if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxImagePixels) {
    fail(std::string(format) + " image too large (" + std::to_string(width) + "x" + std::to_string(height) +
         "; at most " + std::to_string(kMaxImageSide) + " on a side and " + std::to_string(kMaxImagePixels) +
         " pixels)");
  }
}

// Reads the header lines of a Radiance file: returns the offset just past the resolution line.
size_t parseRadianceHeader(const unsigned char* data, size_t size, uint32_t& width, uint32_t& height) {
  constexpr size_t kMaxHeader = 64 * 1024;
  size_t pos = 0;
  auto readLine = [&](std::string& line) {
    line.clear();
    while (pos < size && data[pos] != '\n') {
      if (pos >= kMaxHeader) fail("Radiance HDR header longer than 64 KiB (not an HDR file?)");
      line += static_cast<char>(data[pos++]);
    }
    if (pos >= size) fail("Radiance HDR header ends before the resolution line (truncated file)");
    ++pos;  // the '\n'
  };
  std::string line;
  readLine(line);
  if (line != "#?RADIANCE" && line != "#?RGBE") fail("not a Radiance HDR file (no #?RADIANCE line)");
  while (true) {
    readLine(line);
    if (line.empty()) break;  // an empty line ends the header
    if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe")
      fail("unsupported Radiance format '" + line.substr(7) + "' (only 32-bit_rle_rgbe)");
  }
  readLine(line);
  // Only the standard orientation: rows from the top (-Y), pixels left to right (+X).
  char yAxis[3] = {}, xAxis[3] = {};
  unsigned long h = 0, w = 0;
  int used = 0;
  if (line.size() > 64 || std::sscanf(line.c_str(), "%2s %lu %2s %lu%n", yAxis, &h, xAxis, &w, &used) != 4 ||
      static_cast<size_t>(used) != line.size() || std::string(yAxis) != "-Y" || std::string(xAxis) != "+X") {
    fail("unsupported Radiance resolution line '" + line.substr(0, 64) + "' (expected '-Y H +X W')");
  }
  checkDimensions(w, h, "Radiance HDR");
  width = static_cast<uint32_t>(w);
  height = static_cast<uint32_t>(h);
  return pos;
}

void rgbeToFloat(const unsigned char* rgbe, float* out) {
  if (rgbe[3] == 0) {
    out[0] = out[1] = out[2] = 0.0f;
    return;
  }
  const float f = std::ldexp(1.0f, int(rgbe[3]) - (128 + 8));
  out[0] = rgbe[0] * f;
  out[1] = rgbe[1] * f;
  out[2] = rgbe[2] * f;
}

std::string scanlineMissing(uint32_t row, uint32_t height) {
  return "Radiance HDR data ends in scanline " + std::to_string(row + 1) + " of " + std::to_string(height) +
         " (truncated file)";
}

float srgbToLinear(unsigned char c) {
  const float v = c / 255.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

ImageFormat sniffImageFormat(const unsigned char* data, size_t size) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 8 && std::memcmp(data, png, 8) == 0) return ImageFormat::Png;
  if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) return ImageFormat::Jpeg;
  if ((size >= 10 && std::memcmp(data, "#?RADIANCE", 10) == 0) ||
      (size >= 6 && std::memcmp(data, "#?RGBE", 6) == 0))
    return ImageFormat::RadianceHdr;
  return ImageFormat::Unknown;
}

const char* imageFormatName(ImageFormat f) {
  switch (f) {
    case ImageFormat::RadianceHdr:
      return "Radiance HDR";
    case ImageFormat::Png:
      return "PNG";
    case ImageFormat::Jpeg:
      return "JPEG";
    default:
      return "unknown";
  }
}

FloatImage decodeRadianceHdr(const unsigned char* data, size_t size) {
  FloatImage img;
  size_t pos = parseRadianceHeader(data, size, img.width, img.height);
  const uint32_t w = img.width, h = img.height;
  img.rgb.assign(size_t(w) * h * 3, 0.0f);
  std::vector<unsigned char> line(size_t(w) * 4);
  for (uint32_t row = 0; row < h; ++row) {
    float* out = img.rgb.data() + size_t(row) * w * 3;
    // New-style run-length encoding: a scanline starts with 2, 2 and its width (15 bits). Anything else (and
    // any width that cannot be run-length encoded) means flat RGBE pixels from here to the end of the image.
    const bool rle = w >= 8 && w < 32768 && pos + 4 <= size && data[pos] == 2 && data[pos + 1] == 2 &&
                     (data[pos + 2] & 0x80) == 0;
    if (!rle) {
      const size_t pixels = size_t(h - row) * w;
      if (size - pos < pixels * 4) {
        const size_t complete = (size - pos) / 4 / w;
        fail(scanlineMissing(row + static_cast<uint32_t>(complete), h));
      }
      for (size_t i = 0; i < pixels; ++i) rgbeToFloat(data + pos + 4 * i, out + 3 * i);
      return img;
    }
    if (((uint32_t(data[pos + 2]) << 8) | data[pos + 3]) != w) {
      fail("Radiance HDR scanline " + std::to_string(row + 1) + " has width " +
           std::to_string((uint32_t(data[pos + 2]) << 8) | data[pos + 3]) + ", the image " +
           std::to_string(w));
    }
    pos += 4;
    for (int channel = 0; channel < 4; ++channel) {
      uint32_t x = 0;
      while (x < w) {
        if (pos >= size) fail(scanlineMissing(row, h));
        uint32_t count = data[pos++];
        if (count > 128) {  // a run: one value repeated
          count -= 128;
          if (count > w - x)
            fail("Radiance HDR run longer than its scanline in row " + std::to_string(row + 1));
          if (pos >= size) fail(scanlineMissing(row, h));
          const unsigned char value = data[pos++];
          for (uint32_t i = 0; i < count; ++i) line[4 * (x + i) + channel] = value;
        } else {  // literal values
          if (count == 0 || count > w - x)
            fail("Radiance HDR literal run of " + std::to_string(count) + " bytes is invalid in row " +
                 std::to_string(row + 1));
          if (size - pos < count) fail(scanlineMissing(row, h));
          for (uint32_t i = 0; i < count; ++i) line[4 * (x + i) + channel] = data[pos + i];
          pos += count;
        }
        x += count;
      }
    }
    for (uint32_t x = 0; x < w; ++x) rgbeToFloat(&line[4 * x], out + 3 * x);
  }
  return img;
}

Rgba8Image decodeRgba8(const unsigned char* data, size_t size) {
  const ImageFormat format = sniffImageFormat(data, size);
  Rgba8Image img;
  if (format == ImageFormat::RadianceHdr) {
    const FloatImage f = decodeRadianceHdr(data, size);
    img.width = f.width;
    img.height = f.height;
    img.rgba.resize(size_t(f.width) * f.height * 4);
    for (size_t i = 0; i < size_t(f.width) * f.height; ++i) {
      for (int c = 0; c < 3; ++c) {
        const float z = std::pow(f.rgb[3 * i + c], 1.0f / 2.2f) * 255.0f + 0.5f;
        img.rgba[4 * i + c] = static_cast<unsigned char>(std::clamp(z, 0.0f, 255.0f));
      }
      img.rgba[4 * i + 3] = 255;
    }
    return img;
  }
  if (format != ImageFormat::Png && format != ImageFormat::Jpeg)
    fail("unsupported image format (expected PNG, JPEG or Radiance HDR)");
  if (size > static_cast<size_t>(INT32_MAX)) fail("image file larger than 2 GiB");
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, int(size), &w, &h, &channels)) {
    const char* reason = stbi_failure_reason();
    fail(std::string(imageFormatName(format)) + " header unreadable (" + (reason ? reason : "corrupt") + ")");
  }
  checkDimensions(uint64_t(std::max(w, 0)), uint64_t(std::max(h, 0)), imageFormatName(format));
  int dw = 0, dh = 0;
  stbi_uc* pixels = stbi_load_from_memory(data, int(size), &dw, &dh, &channels, 4);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    fail(std::string(imageFormatName(format)) + " could not be decoded (" + (reason ? reason : "corrupt") +
         ")");
  }
  if (dw != w || dh != h) {
    stbi_image_free(pixels);
    fail(std::string(imageFormatName(format)) + " decoded to another size than its header says");
  }
  img.width = uint32_t(w);
  img.height = uint32_t(h);
  img.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
  stbi_image_free(pixels);
  return img;
}

FloatImage decodeLinearRgb(const unsigned char* data, size_t size) {
  if (sniffImageFormat(data, size) == ImageFormat::RadianceHdr) return decodeRadianceHdr(data, size);
  const Rgba8Image ldr = decodeRgba8(data, size);
  FloatImage img;
  img.width = ldr.width;
  img.height = ldr.height;
  img.rgb.resize(size_t(ldr.width) * ldr.height * 3);
  float table[256];
  for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(static_cast<unsigned char>(i));
  for (size_t i = 0; i < size_t(ldr.width) * ldr.height; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = table[ldr.rgba[4 * i + c]];
  return img;
}

}  // namespace wb
