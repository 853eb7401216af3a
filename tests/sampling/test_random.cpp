// Tests of shaders/shared/random.h with the project's Sobol direction numbers and blue-noise texture.
#include <gtest/gtest.h>

#include <complex>
#include <cstdio>
#include <set>

#include "sampling/blue_noise.h"
#include "sampling/sobol.h"
#include "shared/random.h"
#include "stats.h"

namespace wb {
namespace {

struct SamplerTables {
  std::vector<uint32_t> sobol = sobolDirectionNumbers(static_cast<int>(WB_SOBOL_DIMS));
  std::vector<uint32_t> blue = blueNoise128();
  SamplerTables() {
    gpu::gSobolDirections = sobol.data();
    gpu::gBlueNoise = blue.data();
  }
  ~SamplerTables() {
    gpu::gSobolDirections = nullptr;
    gpu::gBlueNoise = nullptr;
  }
};

TEST(Sobol, PrimitivePolynomials) {
  auto p = primitivePolynomials(12);
  // Known list: x+1; x^2+x+1; x^3+x+1, x^3+x^2+1; x^4+x+1, x^4+x^3+1; degree 5: a = 2,4,7,11,13,14.
  const int deg[] = {1, 2, 3, 3, 4, 4, 5, 5, 5, 5, 5, 5};
  const uint32_t a[] = {0, 1, 1, 2, 1, 4, 2, 4, 7, 11, 13, 14};
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(p[i].degree, deg[i]) << i;
    EXPECT_EQ(p[i].a, a[i]) << i;
  }
  EXPECT_EQ(primitivePolynomials(161).back().degree, 11);
}

TEST(Sobol, FirstPointsMatchKnownSequence) {
  SamplerTables t;
  const float dim0[] = {0.0f, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  const float dim1[] = {0.0f, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};  // index (not Gray) order
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(gpu::sobolSample(i, 0), dim0[i]) << i;
    EXPECT_EQ(gpu::sobolSample(i, 1), dim1[i]) << i;
  }
}

// Every block of 2^m consecutive points (aligned) puts exactly one point in each interval [k/2^m, (k+1)/2^m).
bool stratifies(const std::function<uint32_t(uint32_t)>& bits, uint32_t start, int m) {
  std::vector<uint8_t> seen(1u << m, 0);
  for (uint32_t i = 0; i < (1u << m); ++i) {
    uint32_t cell = bits(start + i) >> (32 - m);
    if (seen[cell]++) return false;
  }
  return true;
}

TEST(Sobol, EveryDimensionIsA0m1Sequence) {
  SamplerTables t;
  for (uint32_t dim = 0; dim < WB_SOBOL_DIMS; ++dim) {
    for (int m = 1; m <= 12; ++m) {
      for (uint32_t block : {0u, 1u, 5u}) {
        uint32_t start = block << m;
        ASSERT_TRUE(stratifies([&](uint32_t i) { return gpu::sobolBits(i, dim); }, start, m))
            << "dim " << dim << " m " << m << " block " << block;
        ASSERT_TRUE(stratifies(
            [&](uint32_t i) { return gpu::nestedUniformScramble(gpu::sobolBits(i, dim), 77u); }, start, m))
            << "owen dim " << dim << " m " << m;
      }
    }
  }
}

TEST(Sobol, TwoDimensionalProjections) {
  auto dirs = sobolDirectionNumbers(static_cast<int>(WB_SOBOL_DIMS));
  // Dims 0/1 form a (0,m,2)-net for every m (the classical pair).
  for (int m = 1; m <= 16; ++m) EXPECT_EQ(sobolPairTValue(dirs, 0, 1, m), 0) << m;
  // Report the t-values the search reached for pairs used together (pixel jitter x BRDF, BRDF direction).
  int worst = 0;
  double mean = 0.0;
  int count = 0;
  for (uint32_t b = 0; b < WB_SOBOL_MAX_BOUNCES; ++b) {
    int d1 = static_cast<int>(gpu::sampleDimension(b, WB_DIM_BRDF));
    int t1 = sobolPairTValue(dirs, d1, d1 + 1, 10);
    int t2 = sobolPairTValue(dirs, static_cast<int>(gpu::sampleDimension(b, WB_DIM_LIGHT)),
                             static_cast<int>(gpu::sampleDimension(b, WB_DIM_LIGHT)) + 1, 10);
    worst = std::max({worst, t1, t2});
    mean += t1 + t2;
    count += 2;
  }
  std::printf("BRDF/light pair t-values at m=10: mean %.2f worst %d\n", mean / count, worst);
  EXPECT_LE(worst, 7);
}

TEST(Sobol, Deterministic) {
  std::vector<uint32_t> all = sobolDirectionNumbers(162);
  EXPECT_EQ(sobolDirectionNumbers(40), std::vector<uint32_t>(all.begin(), all.begin() + 40 * 32));
}

TEST(Sampler, ValuesInUnitIntervalAndStratifiedPerPixel) {
  SamplerTables t;
  const uint32_t n = 256;
  for (bool pcg : {false, true}) {
    for (uint32_t px = 0; px < 200; px += 37) {
      for (uint32_t dim = 0; dim < WB_SOBOL_DIMS + 4; dim += 7) {
        std::vector<uint8_t> seen(n, 0);
        bool strat = true;
        for (uint32_t i = 0; i < n; ++i) {
          gpu::SamplerState s = gpu::samplerInit(glm::uvec2(px, px * 3 + 1), i, 12345u, pcg);
          float v = gpu::samplerGet1D(s, dim);
          ASSERT_GE(v, 0.0f);
          ASSERT_LT(v, 1.0f);
          // Cranley-Patterson rotation keeps the (toroidal) stratification of the Sobol points.
          uint32_t cell = static_cast<uint32_t>(v * n);
          if (seen[cell]++) strat = false;
        }
        if (!pcg && dim < WB_SOBOL_DIMS) {
          EXPECT_TRUE(strat) << "pixel " << px << " dim " << dim;
        }
      }
    }
  }
  EXPECT_LT(gpu::uintToUnitFloat(0xffffffffu), 1.0f);
  // The rotation (and so the first sample) differs between pixels and dimension pairs.
  gpu::SamplerState a = gpu::samplerInit(glm::uvec2(3, 4), 0, 0, false);
  gpu::SamplerState b = gpu::samplerInit(glm::uvec2(4, 4), 0, 0, false);
  EXPECT_NE(gpu::samplerGet1D(a, 2), gpu::samplerGet1D(b, 2));
  EXPECT_NE(gpu::samplerGet1D(a, 2), gpu::samplerGet1D(a, 4));
}

TEST(Sampler, PcgUniformity) {
  std::vector<double> obs(64, 0.0), exp(64, 1e6 / 64);
  uint32_t state = 42u;
  for (int i = 0; i < 1000000; ++i) obs[static_cast<int>(gpu::pcgNextFloat(state) * 64)] += 1.0;
  auto r = test::chiSquareTest(obs, exp);
  EXPECT_GT(r.pValue, 0.01) << r.describe();
  std::fill(obs.begin(), obs.end(), 0.0);
  for (uint32_t i = 0; i < 1000000; ++i) {
    gpu::SamplerState s = gpu::samplerInit(glm::uvec2(i % 1000, i / 1000), 3u, 9u, true);
    obs[static_cast<int>(gpu::samplerGet1D(s, 5) * 64)] += 1.0;
  }
  r = test::chiSquareTest(obs, exp);
  EXPECT_GT(r.pValue, 0.01) << r.describe();
}

// ---- blue noise ----

// Fraction of the spectral energy (DC removed) at radial frequencies below `cutoff` (of size/2).
double lowFrequencyEnergy(const std::vector<double>& img, int size, double cutoff) {
  using C = std::complex<double>;
  std::vector<C> a(img.begin(), img.end());
  double mean = 0.0;
  for (double v : img) mean += v;
  mean /= img.size();
  for (C& c : a) c -= mean;
  std::vector<C> tw(size);
  for (int k = 0; k < size; ++k) tw[k] = std::polar(1.0, -2.0 * std::numbers::pi * k / size);
  std::vector<C> tmp(size);
  for (int pass = 0; pass < 2; ++pass) {  // rows, then columns
    for (int line = 0; line < size; ++line) {
      for (int k = 0; k < size; ++k) {
        C s = 0.0;
        for (int j = 0; j < size; ++j) {
          C v = pass == 0 ? a[line * size + j] : a[j * size + line];
          s += v * tw[(k * j) % size];
        }
        tmp[k] = s;
      }
      for (int k = 0; k < size; ++k) (pass == 0 ? a[line * size + k] : a[k * size + line]) = tmp[k];
    }
  }
  double low = 0.0, total = 0.0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      int fx = x <= size / 2 ? x : x - size;
      int fy = y <= size / 2 ? y : y - size;
      double e = std::norm(a[y * size + x]);
      total += e;
      if (std::sqrt(double(fx * fx + fy * fy)) < cutoff) low += e;
    }
  }
  return low / total;
}

TEST(BlueNoise, CommittedTextureIsTwoPermutations) {
  std::vector<uint32_t> tex = blueNoise128();
  ASSERT_EQ(tex.size(), 128u * 128u);
  for (int ch = 0; ch < 2; ++ch) {
    std::vector<uint8_t> seen(16384, 0);
    for (uint32_t v : tex) {
      uint32_t c = (v >> (16 * ch)) & 0xffffu;
      ASSERT_EQ(c % 4u, 0u);
      ASSERT_EQ(seen[c / 4u]++, 0) << "level " << c / 4u << " repeated in channel " << ch;
    }
  }
}

TEST(BlueNoise, LowFrequencyEnergyBelowWhiteNoise) {
  std::vector<uint32_t> tex = blueNoise128();
  std::vector<double> white(16384);
  std::mt19937 gen(3);
  for (double& w : white) w = std::uniform_real_distribution<double>(0.0, 1.0)(gen);
  double eWhite = lowFrequencyEnergy(white, 128, 16.0);
  for (int ch = 0; ch < 2; ++ch) {
    std::vector<double> img(16384);
    for (size_t i = 0; i < img.size(); ++i) img[i] = ((tex[i] >> (16 * ch)) & 0xffffu) / 65536.0;
    double e = lowFrequencyEnergy(img, 128, 16.0);
    std::printf("blue noise channel %d: low-frequency energy %.4f vs white %.4f\n", ch, e, eWhite);
    EXPECT_LT(e, 0.1 * eWhite);
  }
  // The two channels are independent masks (not identical).
  int same = 0;
  for (uint32_t v : tex) same += (v & 0xffffu) == (v >> 16) ? 1 : 0;
  EXPECT_LT(same, 100);
}

TEST(BlueNoise, GeneratorIsDeterministicAndMatchesCommittedFile) {
  auto small = voidAndCluster(32, 9u);
  EXPECT_EQ(small, voidAndCluster(32, 9u));
  std::set<uint32_t> levels(small.begin(), small.end());
  EXPECT_EQ(levels.size(), 1024u);
  EXPECT_EQ(*levels.rbegin(), 1023u);
#ifndef WB_SLOW_CHECKS_OFF
  EXPECT_EQ(generateBlueNoise128(), blueNoise128()) << "regenerate with tools/sampling (wb_gen_blue_noise)";
#endif
}

}  // namespace
}  // namespace wb
