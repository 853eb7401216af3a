// Bounded image decoding (common/image_decode.h): Radiance HDR against stb_image on a valid file, and every
// malformed file refused with a reason instead of a hang or silently filled rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>
#include <iterator>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "common/file_io.h"
#include "common/image_decode.h"
#include "common/paths.h"

namespace {

using Bytes = std::vector<unsigned char>;

Bytes readAll(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

std::filesystem::path garden() {
  return wb::sharedDir() / "assets/env/chinese_garden_1k.hdr";
}

// A flat (uncompressed) Radiance file: width < 8 is never run-length encoded.
Bytes flatHdr(uint32_t w, uint32_t h) {
  const std::string header =
      "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
  Bytes b(header.begin(), header.end());
  for (uint32_t i = 0; i < w * h; ++i) {
    const unsigned char px[4] = {static_cast<unsigned char>(64 + i % 64), 128, 200, 129};  // ~0.5, 1, 1.56
    b.insert(b.end(), px, px + 4);
  }
  return b;
}

std::string decodeError(const Bytes& b) {
  try {
    wb::decodeRadianceHdr(b.data(), b.size());
  } catch (const wb::ImageDecodeError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageDecode, RadianceMatchesStbImageOnTheGarden) {
  const Bytes bytes = readAll(garden());
  ASSERT_FALSE(bytes.empty());
  const wb::FloatImage img = wb::decodeRadianceHdr(bytes.data(), bytes.size());
  int w = 0, h = 0, c = 0;
  float* ref = stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &w, &h, &c, 3);
  ASSERT_NE(ref, nullptr);
  ASSERT_EQ(int(img.width), w);
  ASSERT_EQ(int(img.height), h);
  size_t differ = 0;
  for (size_t i = 0; i < size_t(w) * h * 3; ++i) differ += img.rgb[i] != ref[i];
  stbi_image_free(ref);
  EXPECT_EQ(differ, 0u);
}

TEST(ImageDecode, TruncatedRunLengthFileIsRefusedNotLooping) {
  const Bytes bytes = readAll(garden());
  for (size_t keep : {bytes.size() / 2, bytes.size() - 1, size_t(200), size_t(40)}) {
    const Bytes cut(bytes.begin(), bytes.begin() + long(keep));
    const std::string e = decodeError(cut);
    EXPECT_NE(e.find("truncated"), std::string::npos) << keep << ": " << e;
  }
}

TEST(ImageDecode, TruncatedFlatFileIsRefusedWithTheMissingScanline) {
  Bytes b = flatHdr(4, 10);
  EXPECT_EQ(decodeError(b), "");
  const wb::FloatImage full = wb::decodeRadianceHdr(b.data(), b.size());
  EXPECT_NEAR(full.rgb[0], 64.0 / 128.0, 1e-6);
  b.resize(b.size() - 4 * 4 * 5);  // five rows missing
  EXPECT_NE(decodeError(b).find("scanline 6 of 10"), std::string::npos) << decodeError(b);
}

TEST(ImageDecode, MalformedRunsAndHeadersAreRefused) {
  // A run-length scanline whose first count is 0 (stb_image 2.27 loops forever on it).
  std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 16\n";
  Bytes zeroRun(header.begin(), header.end());
  for (unsigned char c : {2, 2, 0, 16, 0, 0, 0, 0}) zeroRun.push_back(c);
  EXPECT_NE(decodeError(zeroRun).find("invalid"), std::string::npos) << decodeError(zeroRun);
  // A run longer than the scanline.
  Bytes longRun(header.begin(), header.end());
  for (unsigned char c : {2, 2, 0, 16, 128 + 100, 7}) longRun.push_back(c);
  EXPECT_NE(decodeError(longRun).find("longer than"), std::string::npos) << decodeError(longRun);
  // A scanline that says another width.
  Bytes wrongWidth(header.begin(), header.end());
  for (unsigned char c : {2, 2, 0, 17}) wrongWidth.push_back(c);
  EXPECT_NE(decodeError(wrongWidth).find("width 17"), std::string::npos) << decodeError(wrongWidth);
  // Sizes beyond the bound are refused before anything is allocated.
  const std::string huge = "#?RADIANCE\n\n-Y 100000 +X 100000\n";
  EXPECT_NE(decodeError(Bytes(huge.begin(), huge.end())).find("too large"), std::string::npos);
  const std::string zero = "#?RADIANCE\n\n-Y 0 +X 16\n";
  EXPECT_NE(decodeError(Bytes(zero.begin(), zero.end())).find("no pixels"), std::string::npos);
  const std::string rotated = "#?RADIANCE\n\n+X 16 -Y 16\n";
  EXPECT_NE(decodeError(Bytes(rotated.begin(), rotated.end())).find("resolution"), std::string::npos);
  const std::string xyze = "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n";
  EXPECT_NE(decodeError(Bytes(xyze.begin(), xyze.end())).find("xyze"), std::string::npos);
  const std::string noEnd = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n";
  EXPECT_NE(decodeError(Bytes(noEnd.begin(), noEnd.end())).find("truncated"), std::string::npos);
}

TEST(ImageDecode, PngDimensionsAreCheckedBeforeDecoding) {
  // A PNG header (signature + IHDR) that claims 12000 x 12000 pixels (over kMaxImagePixels, under stb_image's
  // own limit).
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
  for (uint32_t v : {12000u, 12000u})
    for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<unsigned char>(v >> s));
  for (unsigned char c : {8, 6, 0, 0, 0, 0, 0, 0, 0}) png.push_back(c);
  try {
    wb::decodeRgba8(png.data(), png.size());
    FAIL() << "decoded";
  } catch (const wb::ImageDecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();
  }
  const Bytes text = {'h', 'e', 'l', 'l', 'o'};
  EXPECT_THROW(wb::decodeRgba8(text.data(), text.size()), wb::ImageDecodeError);
}

TEST(ImageDecode, HdrBytesAsAn8BitTextureMatchStbImage) {
  const Bytes b = flatHdr(4, 3);
  const wb::Rgba8Image img = wb::decodeRgba8(b.data(), b.size());
  int w = 0, h = 0, c = 0;
  unsigned char* ref = stbi_load_from_memory(b.data(), int(b.size()), &w, &h, &c, 4);
  ASSERT_NE(ref, nullptr);
  ASSERT_EQ(img.rgba.size(), size_t(w) * h * 4);
  for (size_t i = 0; i < img.rgba.size(); ++i) EXPECT_NEAR(int(img.rgba[i]), int(ref[i]), 1) << i;
  stbi_image_free(ref);
}

TEST(FileIo, NamedPipeIsRefusedWithoutBlocking) {
  const auto dir = std::filesystem::temp_directory_path() / ("wb_file_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  std::string why;
  EXPECT_FALSE(wb::readRegularFile(fifo, &why).has_value());
  EXPECT_NE(why.find("named pipe"), std::string::npos) << why;
  EXPECT_FALSE(wb::readRegularFile(dir, &why).has_value());
  EXPECT_THROW(wb::requireWritableFile(dir, "--out"), std::runtime_error);
  EXPECT_THROW(wb::requireWritableFile("/etc/hostname/x.png", "--out"), std::runtime_error);
  EXPECT_THROW(wb::requireWritableFile("/proc/x.json", "--stats"), std::runtime_error);
  wb::requireWritableFile(dir / "new.png", "--out");
  EXPECT_FALSE(std::filesystem::exists(dir / "new.png"));  // the probe leaves nothing behind
  std::filesystem::remove_all(dir);
}

}  // namespace
