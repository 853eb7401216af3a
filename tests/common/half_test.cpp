// halfToFloat against values whose binary16 encodings are known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/half.h"

TEST(Half, KnownEncodingsDecodeExactly) {
  EXPECT_EQ(wb::halfToFloat(0x0000), 0.0f);
  EXPECT_TRUE(std::signbit(wb::halfToFloat(0x8000)));  // -0
  EXPECT_EQ(wb::halfToFloat(0x3C00), 1.0f);
  EXPECT_EQ(wb::halfToFloat(0xC000), -2.0f);
  EXPECT_EQ(wb::halfToFloat(0x3555), 0.333251953125f);           // nearest half to 1/3
  EXPECT_EQ(wb::halfToFloat(0x7BFF), 65504.0f);                  // largest finite
  EXPECT_EQ(wb::halfToFloat(0x0400), std::ldexp(1.0f, -14));     // smallest normal
  EXPECT_EQ(wb::halfToFloat(0x0001), std::ldexp(1.0f, -24));     // smallest subnormal
  EXPECT_EQ(wb::halfToFloat(0x03FF), std::ldexp(1023.0f, -24));  // largest subnormal
  EXPECT_EQ(wb::halfToFloat(0x7C00), std::numeric_limits<float>::infinity());
  EXPECT_EQ(wb::halfToFloat(0xFC00), -std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(wb::halfToFloat(0x7E00)));
  EXPECT_TRUE(std::isnan(wb::halfToFloat(0x7C01)));
}

TEST(Half, BytesDecodeInOrder) {
  const uint16_t halves[] = {0x3C00, 0x4000, 0xBC00};
  std::vector<uint8_t> bytes(sizeof halves + 1);  // a trailing odd byte is ignored
  std::memcpy(bytes.data(), halves, sizeof halves);
  EXPECT_EQ(wb::halvesToFloats(bytes), (std::vector<float>{1.0f, 2.0f, -1.0f}));
}
