#include <gtest/gtest.h>

#include "vk/sbt.h"

using wb::vk::alignUp;
using wb::vk::computeSbtLayout;

namespace {

struct Props {
  uint32_t handleSize, handleAlignment, baseAlignment;
};

// Checks every rule of the Vulkan spec for vkCmdTraceRaysKHR's regions.
void checkLayout(const Props& p, uint32_t miss, uint32_t hit, uint32_t callable, uint32_t data) {
  SCOPED_TRACE(::testing::Message() << "handle " << p.handleSize << " align " << p.handleAlignment << " base "
                                    << p.baseAlignment << " miss " << miss << " hit " << hit << " data "
                                    << data);
  auto l = computeSbtLayout(p.handleSize, p.handleAlignment, p.baseAlignment, miss, hit, callable, data);
  const wb::vk::SbtRegion* regions[] = {&l.raygen, &l.miss, &l.hit, &l.callable};
  const uint32_t counts[] = {1, miss, hit, callable};
  uint64_t end = 0;
  for (int i = 0; i < 4; ++i) {
    const auto& r = *regions[i];
    EXPECT_EQ(r.count, counts[i]);
    if (counts[i] == 0) {
      EXPECT_EQ(r.size, 0u);
      EXPECT_EQ(r.stride, 0u);
      continue;
    }
    EXPECT_EQ(r.offset % p.baseAlignment, 0u) << "region start must be base-aligned";
    EXPECT_EQ(r.stride % p.handleAlignment, 0u) << "stride must be a multiple of the handle alignment";
    EXPECT_GE(r.stride, uint64_t(p.handleSize) + data) << "a record must fit in its stride";
    EXPECT_GE(r.size, r.count * r.stride) << "all records must fit";
    EXPECT_GE(r.offset, end) << "regions must not overlap";
    end = r.offset + r.size;
  }
  EXPECT_EQ(l.raygen.size, l.raygen.stride) << "raygen size must equal its stride";
  EXPECT_GE(l.totalSize, end);
  EXPECT_EQ(l.totalSize % p.baseAlignment, 0u);
}

}  // namespace

TEST(Sbt, AlignUp) {
  EXPECT_EQ(alignUp(0, 32), 0u);
  EXPECT_EQ(alignUp(1, 32), 32u);
  EXPECT_EQ(alignUp(32, 32), 32u);
  EXPECT_EQ(alignUp(33, 16), 48u);
}

TEST(Sbt, LavapipeLayoutExact) {
  // lavapipe: handle 32, handle alignment 16, base alignment 32; raygen + 2 miss + 1 hit group.
  auto l = computeSbtLayout(32, 16, 32, 2, 1, 0);
  EXPECT_EQ(l.raygen.offset, 0u);
  EXPECT_EQ(l.raygen.stride, 32u);
  EXPECT_EQ(l.raygen.size, 32u);
  EXPECT_EQ(l.miss.offset, 32u);
  EXPECT_EQ(l.miss.stride, 32u);
  EXPECT_EQ(l.miss.size, 64u);
  EXPECT_EQ(l.hit.offset, 96u);
  EXPECT_EQ(l.hit.size, 32u);
  EXPECT_EQ(l.totalSize, 128u);
}

TEST(Sbt, NvidiaLayoutExact) {
  // NVIDIA (measured on the H100): handle 32, handle alignment 32, base alignment 64.
  auto l = computeSbtLayout(32, 32, 64, 2, 1, 0);
  EXPECT_EQ(l.raygen.stride, 64u);
  EXPECT_EQ(l.raygen.size, 64u);
  EXPECT_EQ(l.miss.offset, 64u);
  EXPECT_EQ(l.miss.stride, 32u);
  EXPECT_EQ(l.miss.size, 64u);
  EXPECT_EQ(l.hit.offset, 128u);
  EXPECT_EQ(l.hit.stride, 32u);
  EXPECT_EQ(l.hit.size, 64u);
  EXPECT_EQ(l.totalSize, 192u);
}

TEST(Sbt, ManyHandleSizesAndAlignments) {
  const Props props[] = {{32, 16, 32}, {32, 32, 64}, {16, 16, 16}, {32, 64, 64}, {64, 64, 256}, {8, 4, 32}};
  for (const auto& p : props) {
    for (uint32_t miss : {1u, 2u, 5u}) {
      for (uint32_t hit : {1u, 3u, 7u}) {
        for (uint32_t callable : {0u, 2u}) {
          for (uint32_t data : {0u, 4u, 20u}) checkLayout(p, miss, hit, callable, data);
        }
      }
    }
  }
}

TEST(Sbt, RejectsBadProperties) {
  EXPECT_THROW(computeSbtLayout(0, 16, 32, 1, 1, 0), std::invalid_argument);
  EXPECT_THROW(computeSbtLayout(32, 24, 32, 1, 1, 0), std::invalid_argument);
  EXPECT_THROW(computeSbtLayout(32, 16, 0, 1, 1, 0), std::invalid_argument);
}
