// Image decoding with bounds: every size is checked before memory is allocated or a pixel is read. Radiance
// .hdr (RGBE) is decoded here, not by stb_image 2.27, which loops forever on some truncated files
// (CVE-2021-42715) and fills the missing rows of a truncated uncompressed file silently. PNG and JPEG go to
// stb_image after their dimensions were read from the header and checked.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace wb {

// The largest image any decode accepts: 32768 on a side and 2^27 pixels (512 MiB as RGBA8, 1.5 GiB as RGB
// float).
inline constexpr uint32_t kMaxImageSide = 32768;
inline constexpr uint64_t kMaxImagePixels = uint64_t{1} << 27;

struct ImageDecodeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class ImageFormat { Unknown, RadianceHdr, Png, Jpeg };
// By the file's first bytes.
ImageFormat sniffImageFormat(const unsigned char* data, size_t size);
const char* imageFormatName(ImageFormat f);  // "Radiance HDR", "PNG", "JPEG", "unknown"

struct FloatImage {
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;  // width * height * 3, row 0 at the top
};

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<unsigned char> rgba;  // width * height * 4, row 0 at the top
};

// Radiance RGBE (FORMAT=32-bit_rle_rgbe, "-Y H +X W"): flat and run-length encoded scanlines. Every header
// line, size, run and scanline is checked against the data; a file that ends before its last scanline is
// refused (ImageDecodeError naming the scanline). Values are those stb_image gives (mantissa * 2^(e-136)).
FloatImage decodeRadianceHdr(const unsigned char* data, size_t size);

// PNG or JPEG as RGBA8 (dimensions checked from the header first), or Radiance HDR mapped to 8 bits as
// stb_image does (v^(1/2.2), clamped). Throws ImageDecodeError with the reason.
Rgba8Image decodeRgba8(const unsigned char* data, size_t size);

// Linear RGB floats: Radiance HDR as stored; PNG and JPEG decoded from sRGB to linear (at most 1).
FloatImage decodeLinearRgb(const unsigned char* data, size_t size);

}  // namespace wb
