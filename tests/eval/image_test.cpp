// The PNG tonemapper (eval/image.h): very bright radiance maps to white with every curve, never to NaN ->
// black; NaN and negative values are black.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eval/image.h"

namespace {

wb::eval::ImageRGBA onePixel(float v) {
  wb::eval::ImageRGBA img;
  img.width = img.height = 1;
  img.pixels = {v, v, v, 1.0f};
  return img;
}

TEST(Tonemap, HugeAndInfiniteRadianceIsWhite) {
  const float inf = std::numeric_limits<float>::infinity();
  for (auto op : {wb::eval::Tonemap::Clamp, wb::eval::Tonemap::Reinhard, wb::eval::Tonemap::Aces}) {
    for (float v : {1e4f, 1e20f, 1e30f, 3e38f, std::numeric_limits<float>::max(), inf}) {
      for (float stops : {0.0f, 8.0f}) {
        const auto px = wb::eval::tonemapToSrgb8(onePixel(v), stops, op);
        EXPECT_EQ(int(px[0]), 255) << wb::eval::tonemapName(op) << " v=" << v << " stops=" << stops;
      }
    }
    EXPECT_EQ(int(wb::eval::tonemapToSrgb8(onePixel(std::nanf("")), 0.0f, op)[0]), 0);
    EXPECT_EQ(int(wb::eval::tonemapToSrgb8(onePixel(-inf), 0.0f, op)[0]), 0);
    EXPECT_EQ(int(wb::eval::tonemapToSrgb8(onePixel(-1.0f), 0.0f, op)[0]), 0);
    EXPECT_EQ(int(wb::eval::tonemapToSrgb8(onePixel(0.0f), 0.0f, op)[0]), 0);
  }
  // The ordinary range is unchanged: 0.18 through ACES, then sRGB.
  EXPECT_NEAR(int(wb::eval::tonemapToSrgb8(onePixel(0.18f))[0]), 141, 1);  // ACES(0.18) = 0.267
}

}  // namespace
