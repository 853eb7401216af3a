// Tests of shaders/shared/random.h with the project's Sobol direction numbers and blue-noise texture: the
// Sobol, PCG and owen (Owen-scrambled Sobol sets) samplers.
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
          gpu::SamplerState s = gpu::samplerInit(glm::uvec2(px, px * 3 + 1), i, 12345u,
                                                 pcg ? WB_SAMPLER_PCG : WB_SAMPLER_SOBOL);
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
  gpu::SamplerState a = gpu::samplerInit(glm::uvec2(3, 4), 0, 0, WB_SAMPLER_SOBOL);
  gpu::SamplerState b = gpu::samplerInit(glm::uvec2(4, 4), 0, 0, WB_SAMPLER_SOBOL);
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
    gpu::SamplerState s = gpu::samplerInit(glm::uvec2(i % 1000, i / 1000), 3u, 9u, WB_SAMPLER_PCG);
    obs[static_cast<int>(gpu::samplerGet1D(s, 5) * 64)] += 1.0;
  }
  r = test::chiSquareTest(obs, exp);
  EXPECT_GT(r.pValue, 0.01) << r.describe();
}

// ---- owen: Owen-scrambled Sobol sets ----

TEST(Owen, SobolDimension1ClosedFormMatchesTheTable) {
  SamplerTables t;
  for (uint32_t i = 0; i < (1u << 16); ++i) {
    ASSERT_EQ(gpu::sobolDim1Reversed(glm::bitfieldReverse(i)), gpu::sobolBits(i, 1)) << i;
  }
  for (uint32_t i : {0xffffffffu, 0x80000001u, 0x12345678u}) {
    EXPECT_EQ(gpu::sobolDim1Reversed(glm::bitfieldReverse(i)), gpu::sobolBits(i, 1)) << i;
  }
}

// The nested uniform scramble is a bijection that keeps every aligned block of 2^m values (m <= 32) together:
// bit i of the output depends only on bits i and above of the input.
TEST(Owen, NestedUniformScrambleIsANestedPermutation) {
  for (uint32_t seed : {1u, 0x9e3779b9u, gpu::pcgHash(5u)}) {
    std::vector<uint8_t> seen(1u << 16, 0);
    for (uint32_t x = 0; x < (1u << 16); ++x) {
      const uint32_t y = gpu::nestedUniformScramble(x << 16, seed);
      ASSERT_EQ(seen[y >> 16]++, 0) << "not a permutation of the top 16 bits";
      // Same top m bits in, same top m bits out.
      for (int m : {1, 4, 9}) {
        const uint32_t other = gpu::nestedUniformScramble((x << 16) ^ (1u << (31 - m)), seed);
        ASSERT_EQ(y >> (32 - m), other >> (32 - m)) << "bit " << m << " changed a higher output bit";
      }
    }
  }
}

// Within one pixel, the first 2^m samples of every coordinate are stratified in 1D, and each 2D set is a
// (0,m,2)-net: one point in every elementary interval [a/2^j, (a+1)/2^j) x [b/2^(m-j), (b+1)/2^(m-j)) - for
// every m, so at every power-of-two sample count, and for the next block of 2^m samples too.
TEST(Owen, SetsAreScrambledZeroMTwoNetsAtEveryPowerOfTwo) {
  SamplerTables t;
  const std::pair<uint32_t, uint32_t> pairs[] = {
      {WB_DIM_PIXEL, WB_DIM_PIXEL + 1u},
      {gpu::sampleDimension(0, WB_DIM_BRDF), gpu::sampleDimension(0, WB_DIM_BRDF) + 1u},
      {gpu::sampleDimension(0, WB_DIM_LIGHT + 1u), gpu::sampleDimension(0, WB_DIM_LIGHT + 2u)},
      {gpu::sampleDimension(7, WB_DIM_BRDF), gpu::sampleDimension(7, WB_DIM_BRDF) + 1u},
      {gpu::sampleDimension(40, WB_DIM_LIGHT + 1u), gpu::sampleDimension(40, WB_DIM_LIGHT + 2u)},
  };
  for (uint32_t px = 0; px < 5; ++px) {
    const glm::uvec2 pixel(px * 37u, px * 11u + 3u);
    for (const auto& [dx, dy] : pairs) {
      for (int m = 0; m <= 10; ++m) {
        for (uint32_t block = 0; block < 2; ++block) {
          const uint32_t n = 1u << m;
          std::vector<std::pair<uint32_t, uint32_t>> pts;
          for (uint32_t i = block * n; i < (block + 1) * n; ++i) {
            const gpu::SamplerState s = gpu::samplerInit(pixel, i, 42u, WB_SAMPLER_OWEN);
            const float x = gpu::samplerGet1D(s, dx), y = gpu::samplerGet1D(s, dy);
            ASSERT_GE(x, 0.0f);
            ASSERT_LT(x, 1.0f);
            pts.emplace_back(uint32_t(x * 4294967296.0), uint32_t(y * 4294967296.0));
          }
          for (int j = 0; j <= m; ++j) {
            std::vector<uint8_t> seen(n, 0);
            for (const auto& [x, y] : pts) {
              const uint32_t cx = j == 0 ? 0u : x >> (32 - j);
              const uint32_t cy = m - j == 0 ? 0u : y >> (32 - (m - j));
              ASSERT_EQ(seen[(cx << (m - j)) | cy]++, 0)
                  << "dims " << dx << "," << dy << " pixel " << px << " m " << m << " block " << block
                  << ": two points in one " << j << "/" << m - j << " elementary interval";
            }
          }
        }
      }
    }
  }
  // The 1D sets (lobe, light choice, Russian roulette) are stratified too.
  for (uint32_t k : {uint32_t(WB_DIM_LOBE), uint32_t(WB_DIM_LIGHT_CHOICE), uint32_t(WB_DIM_RR)}) {
    const uint32_t dim = gpu::sampleDimension(3, k);
    ASSERT_TRUE(stratifies(
        [&](uint32_t i) {
          return uint32_t(gpu::samplerGet1D(gpu::samplerInit(glm::uvec2(9, 9), i, 1u, WB_SAMPLER_OWEN), dim) *
                          4294967296.0);
        },
        0, 8))
        << "dim " << dim;
  }
}

// Every pixel and seed is an independent randomisation: a given sample's values over many pixels are uniform
// (chi-square), seeds give different values, and two sets of one path are independent of each other (their
// joint 2D histogram over pixels and samples is uniform: the per-set index shuffle decorrelates them).
TEST(Owen, PixelsAreIndependentUniformRandomisations) {
  const int bins = 16;
  const uint32_t pixels = 256u * 64u;
  std::vector<double> expected1(bins, double(pixels) / bins);
  for (uint32_t dim :
       {0u, 1u, gpu::sampleDimension(0, WB_DIM_LOBE), gpu::sampleDimension(2, WB_DIM_LIGHT + 2u)}) {
    for (uint32_t index : {0u, 5u}) {
      std::vector<double> obs(bins, 0.0);
      for (uint32_t p = 0; p < pixels; ++p) {
        const gpu::SamplerState s =
            gpu::samplerInit(glm::uvec2(p % 256u, p / 256u), index, 3u, WB_SAMPLER_OWEN);
        obs[int(gpu::samplerGet1D(s, dim) * bins)] += 1.0;
      }
      const auto r = test::chiSquareTest(obs, expected1);
      EXPECT_GT(r.pValue, 1e-3) << "dim " << dim << " index " << index << ": " << r.describe();
    }
  }
  // The bits below the shuffle's 2^-16 resolution are uniform too (Owen scrambling randomises every digit).
  for (uint32_t dim : {0u, 1u, gpu::sampleDimension(0, WB_DIM_BRDF) + 1u}) {
    std::vector<double> obs(bins, 0.0);
    for (uint32_t p = 0; p < pixels; ++p) {
      const gpu::SamplerState s = gpu::samplerInit(glm::uvec2(p % 256u, p / 256u), 0u, 3u, WB_SAMPLER_OWEN);
      const double v = gpu::samplerGet1D(s, dim) * 65536.0;
      obs[int((v - std::floor(v)) * bins)] += 1.0;
    }
    const auto r = test::chiSquareTest(obs, expected1);
    EXPECT_GT(r.pValue, 1e-3) << "dim " << dim << " below 2^-16: " << r.describe();
  }
  // Seeds change every value.
  const gpu::SamplerState s1 = gpu::samplerInit(glm::uvec2(1, 2), 0, 1u, WB_SAMPLER_OWEN);
  const gpu::SamplerState s2 = gpu::samplerInit(glm::uvec2(1, 2), 0, 2u, WB_SAMPLER_OWEN);
  for (uint32_t dim = 0; dim < 40; ++dim) EXPECT_NE(gpu::samplerGet1D(s1, dim), gpu::samplerGet1D(s2, dim));
}

// Two sets of one path are independent within a pixel (the per-set index shuffle decorrelates them): the
// estimate of P(x < 1/2, y < 1/2) = 1/4 from 16 samples of a pixel has at most the variance of independent
// samples (3/256). Without the shuffle, sets that use the same Sobol dimension are scrambled copies of one
// sequence and the estimate is 0 or 1/2.
TEST(Owen, SetsOfOnePathAreDecorrelated) {
  const std::pair<uint32_t, uint32_t> pairs[] = {
      {0u, gpu::sampleDimension(0, WB_DIM_BRDF)},                                          // pixel x, BRDF u
      {gpu::sampleDimension(0, WB_DIM_BRDF), gpu::sampleDimension(0, WB_DIM_LIGHT + 1u)},  // BRDF u, light u
      {gpu::sampleDimension(0, WB_DIM_BRDF) + 1u,
       gpu::sampleDimension(1, WB_DIM_BRDF) + 1u},                                         // bounce 0 vs 1
      {gpu::sampleDimension(0, WB_DIM_LIGHT_CHOICE), gpu::sampleDimension(0, WB_DIM_RR)},  // two 1D sets
  };
  for (const auto& [a, b] : pairs) {
    double sum = 0, sum2 = 0;
    const int pixels = 4096;
    for (int p = 0; p < pixels; ++p) {
      int inside = 0;
      for (uint32_t i = 0; i < 16; ++i) {
        const gpu::SamplerState s = gpu::samplerInit(glm::uvec2(p % 64, p / 64), i, 8u, WB_SAMPLER_OWEN);
        inside += gpu::samplerGet1D(s, a) < 0.5f && gpu::samplerGet1D(s, b) < 0.5f;
      }
      sum += inside / 16.0;
      sum2 += (inside / 16.0) * (inside / 16.0);
    }
    const double mean = sum / pixels, var = sum2 / pixels - mean * mean;
    std::printf("dims %u, %u: mean %.4f variance %.5f (independent samples: 0.01172)\n", a, b, mean, var);
    EXPECT_NEAR(mean, 0.25, 0.01);
    EXPECT_LT(var, 1.2 * 3.0 / 256.0) << "dims " << a << ", " << b;
  }
}

// Stratification pays: the error of a smooth 2D integral over 64 samples per pixel is far below independent
// sampling's (scrambled nets: variance O(n^-3) for smooth integrands), and its mean over pixels is unbiased.
TEST(Owen, SmoothIntegralErrorFarBelowMonteCarlo) {
  auto f = [](float x, float y) { return double(std::exp(x) * std::sin(3.0f * y + 0.5f)); };
  const double exact = (std::exp(1.0) - 1.0) * (std::cos(0.5) - std::cos(3.5)) / 3.0;
  double mseOwen = 0, msePcg = 0, meanOwen = 0;
  const int pixels = 2000;
  for (int p = 0; p < pixels; ++p) {
    double sumO = 0, sumP = 0;
    for (uint32_t i = 0; i < 64; ++i) {
      const gpu::SamplerState so = gpu::samplerInit(glm::uvec2(p, 7), i, 1u, WB_SAMPLER_OWEN);
      const gpu::SamplerState sp = gpu::samplerInit(glm::uvec2(p, 7), i, 1u, WB_SAMPLER_PCG);
      const uint32_t d = gpu::sampleDimension(2, WB_DIM_BRDF);
      sumO += f(gpu::samplerGet1D(so, d), gpu::samplerGet1D(so, d + 1u));
      sumP += f(gpu::samplerGet1D(sp, d), gpu::samplerGet1D(sp, d + 1u));
    }
    mseOwen += std::pow(sumO / 64.0 - exact, 2.0) / pixels;
    msePcg += std::pow(sumP / 64.0 - exact, 2.0) / pixels;
    meanOwen += sumO / 64.0 / pixels;
  }
  std::printf("64 samples: MSE owen %.3g, pcg %.3g (ratio %.0f); mean over pixels %.6f (exact %.6f)\n",
              mseOwen, msePcg, msePcg / mseOwen, meanOwen, exact);
  EXPECT_LT(mseOwen, msePcg / 100.0);
  EXPECT_NEAR(meanOwen, exact, 4.0 * std::sqrt(mseOwen / pixels));
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
