// The denoiser (render/denoiser.h) on analytic images uploaded as the path tracer's images would be: a flat
// image stays flat, an edge in albedo, normal or depth is kept, noise of known variance is reduced by the
// factor the a-trous kernel predicts, the output hands over to the raw mean as the samples grow (consistency
// by construction), and on a real render at many samples the denoised image is the raw one within its noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "render/denoiser.h"
#include "render/path_tracer.h"
#include "vk/context.h"

using namespace wb;

namespace {

uint16_t floatToHalf(float f) {
  // Round to nearest for the normal range the tests use (albedo, normals, depths).
  uint32_t x;
  std::memcpy(&x, &f, 4);
  const uint32_t sign = (x >> 16) & 0x8000u;
  const int exponent = int((x >> 23) & 0xffu) - 127 + 15;
  uint32_t mantissa = x & 0x7fffffu;
  if (exponent <= 0) return uint16_t(sign);  // below the normal range: zero
  uint32_t h = (uint32_t(exponent) << 10) | (mantissa >> 13);
  if (mantissa & 0x1000u) ++h;  // round half up
  return uint16_t(sign | h);
}

float luminance(glm::vec3 c) {
  return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

// What the path tracer would hand the denoiser, per pixel.
struct Frame {
  uint32_t width = 0, height = 0;
  std::vector<glm::vec3> mean;      // accumulated mean radiance
  std::vector<float> samples;       // samples in the pixel
  std::vector<float> meanVariance;  // variance of the mean's luminance (the stats AOV is made from it)
  std::vector<glm::vec3> albedo, normal;
  std::vector<float> depth;

  Frame(uint32_t w, uint32_t h, float n) : width(w), height(h) {
    const size_t count = size_t(w) * h;
    mean.assign(count, glm::vec3(0.5f));
    samples.assign(count, n);
    meanVariance.assign(count, 0.0f);
    albedo.assign(count, glm::vec3(0.5f));
    normal.assign(count, glm::vec3(0, 0, 1));
    depth.assign(count, 2.0f);
  }
  size_t at(uint32_t x, uint32_t y) const { return size_t(y) * width + x; }
};

struct DenoiserFixture : ::testing::Test {
  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<shader::ShaderLibrary> lib;
  std::unique_ptr<render::Denoiser> denoiser;
  vk::Image radiance, albedo, normal, stats;

  void SetUp() override {
    vk::ContextOptions o;
    o.validation = true;
    ctx = std::make_unique<vk::Context>(o);
    lib = std::make_unique<shader::ShaderLibrary>(shader::ShaderLibrary::Options{
        .includeRoots = {shaderDir()}, .cacheDir = {}, .printWarnings = false});
    denoiser = std::make_unique<render::Denoiser>(*ctx, *lib);
  }
  void TearDown() override {
    denoiser.reset();
    radiance = {};
    albedo = {};
    normal = {};
    stats = {};
    lib.reset();
    if (ctx) {
      EXPECT_EQ(ctx->validationErrors(), 0u);
      for (const auto& m : ctx->validationMessages()) ADD_FAILURE() << "validation: " << m;
    }
    ctx.reset();
  }

  // Uploads the frame as the path tracer's images, runs the denoiser and reads its output (rgb per pixel).
  std::vector<glm::vec3> denoise(const Frame& f, const render::DenoiseOptions& options) {
    const size_t count = size_t(f.width) * f.height;
    std::vector<float> rad(4 * count), st(4 * count, 0.0f);
    std::vector<uint16_t> alb(4 * count), nrm(4 * count);
    for (size_t i = 0; i < count; ++i) {
      const float n = f.samples[i], lum = luminance(f.mean[i]);
      for (int c = 0; c < 3; ++c) {
        rad[4 * i + c] = f.mean[i][c];
        alb[4 * i + c] = floatToHalf(f.albedo[i][c]);
        nrm[4 * i + c] = floatToHalf(f.normal[i][c]);
      }
      rad[4 * i + 3] = n;
      alb[4 * i + 3] = 0;
      nrm[4 * i + 3] = floatToHalf(f.depth[i]);
      // The mean of luminance^2 whose sample variance makes the mean's variance meanVariance.
      const float perSample = f.meanVariance[i] * n;
      st[4 * i] = lum * lum + (n > 1.0f ? perSample * (n - 1.0f) / n : 0.0f);
    }
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    radiance = vk::Image(*ctx, f.width, f.height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    stats = vk::Image(*ctx, f.width, f.height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    albedo = vk::Image(*ctx, f.width, f.height, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
    normal = vk::Image(*ctx, f.width, f.height, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
    radiance.upload(rad.data(), rad.size() * 4, VK_IMAGE_LAYOUT_GENERAL);
    stats.upload(st.data(), st.size() * 4, VK_IMAGE_LAYOUT_GENERAL);
    albedo.upload(alb.data(), alb.size() * 2, VK_IMAGE_LAYOUT_GENERAL);
    normal.upload(nrm.data(), nrm.size() * 2, VK_IMAGE_LAYOUT_GENERAL);
    denoiser->resize(f.width, f.height);
    denoiser->setInputs({radiance.view(), albedo.view(), normal.view(), stats.view()});
    denoiser->setOptions(options);
    ctx->submitAndWait([&](VkCommandBuffer cmd) { denoiser->record(cmd); });
    const auto out = denoiser->readOutput();
    std::vector<glm::vec3> rgb(count);
    for (size_t i = 0; i < count; ++i) {
      rgb[i] = {out[4 * i], out[4 * i + 1], out[4 * i + 2]};
      EXPECT_EQ(out[4 * i + 3], f.samples[i]) << "alpha carries the samples per pixel";
    }
    return rgb;
  }
};

// The filter alone: no luminance edge-stopping, no hand-over (what the geometry and the albedo keep).
render::DenoiseOptions geometryOnly(uint32_t iterations = 5) {
  render::DenoiseOptions o;
  o.iterations = iterations;
  o.sigmaLuminance = 0.0f;
  o.handoverTau = -1.0f;
  return o;
}

// Grey noise of standard deviation sigma (relative to the irradiance) on every pixel, the variance recorded.
void addIrradianceNoise(Frame& f, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, sigma);
  for (size_t i = 0; i < f.mean.size(); ++i) {
    const glm::vec3 irradiance = f.mean[i] / f.albedo[i];
    f.mean[i] = f.albedo[i] * (irradiance + gauss(rng));
    const float l = luminance(f.albedo[i]) * sigma;
    f.meanVariance[i] = l * l;
  }
}

// The variance reduction of the linear a-trous filter (B3 spline, steps 1, 2, 4, ...) away from the borders:
// the sum of the squared weights of the composed 2D kernel (separable: the square of the 1D sum).
double expectedVarianceFactor(uint32_t iterations) {
  const double b3[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
  std::vector<double> k{1.0};
  for (uint32_t i = 0; i < iterations; ++i) {
    const size_t step = size_t(1) << i;
    std::vector<double> next(k.size() + 4 * step, 0.0);
    for (size_t a = 0; a < k.size(); ++a)
      for (size_t t = 0; t < 5; ++t) next[a + t * step] += k[a] * b3[t];
    k = std::move(next);
  }
  double sum2 = 0;
  for (double w : k) sum2 += w * w;
  return sum2 * sum2;
}

}  // namespace

TEST_F(DenoiserFixture, AFlatImageStaysFlat) {
  Frame f(48, 40, 8.0f);
  for (size_t i = 0; i < f.mean.size(); ++i) {
    f.albedo[i] = {0.6f, 0.5f, 0.4f};
    f.mean[i] = {0.3f, 0.5f, 0.7f};
    f.meanVariance[i] = 0.05f;  // noisy according to its samples, yet every pixel holds the same value
  }
  const auto out = denoise(f, render::DenoiseOptions{});
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out[i][c], f.mean[i][c], 1e-5f * f.mean[i][c]) << "pixel " << i;
  // Another size on the same denoiser (its images grow to the larger height, the width stays larger).
  Frame g(32, 56, 2.0f);
  for (auto& m : g.mean) m = {0.2f, 0.2f, 0.1f};
  const auto out2 = denoise(g, render::DenoiseOptions{});
  ASSERT_EQ(out2.size(), size_t(32) * 56);
  for (size_t i = 0; i < out2.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(out2[i][c], g.mean[i][c], 1e-5f * g.mean[i][c]) << "pixel " << i;
}

TEST_F(DenoiserFixture, AnEdgeInAlbedoIsKept) {
  // Left red, right blue, the same noisy irradiance of 1 behind both: demodulation filters the irradiance
  // only.
  Frame f(64, 64, 4.0f);
  const glm::vec3 left(0.8f, 0.2f, 0.2f), right(0.2f, 0.2f, 0.8f);
  for (uint32_t y = 0; y < f.height; ++y)
    for (uint32_t x = 0; x < f.width; ++x) {
      f.albedo[f.at(x, y)] = x < f.width / 2 ? left : right;
      f.mean[f.at(x, y)] = f.albedo[f.at(x, y)];
    }
  const Frame noiseless = f;
  addIrradianceNoise(f, 0.3f, 1);
  const auto out = denoise(f, geometryOnly());
  // The columns either side of the edge keep their own colour: a blur across would mix red and blue by ~1/3.
  for (uint32_t x : {f.width / 2 - 1, f.width / 2}) {
    double err2 = 0, raw2 = 0;
    for (uint32_t y = 0; y < f.height; ++y) {
      const size_t i = f.at(x, y);
      for (int c = 0; c < 3; ++c) {
        err2 += std::pow(out[i][c] - noiseless.mean[i][c], 2.0);
        raw2 += std::pow(f.mean[i][c] - noiseless.mean[i][c], 2.0);
      }
      EXPECT_NEAR(out[i].r, noiseless.mean[i].r, 0.1f) << x << "," << y;
      EXPECT_NEAR(out[i].b, noiseless.mean[i].b, 0.1f) << x << "," << y;
    }
    EXPECT_LT(err2, 0.1 * raw2) << "column " << x << ": the noise is filtered up to the edge";
  }
}

// A radiance edge that only the normals (or only the depths) show, with noise on both sides: the filter keeps
// it with no luminance edge-stopping at all.
class DenoiserGeometryEdge : public DenoiserFixture, public ::testing::WithParamInterface<bool> {};

TEST_P(DenoiserGeometryEdge, IsKept) {
  const bool byNormal = GetParam();
  Frame f(64, 64, 4.0f);
  for (uint32_t y = 0; y < f.height; ++y)
    for (uint32_t x = 0; x < f.width; ++x) {
      const size_t i = f.at(x, y);
      const bool left = x < f.width / 2;
      f.mean[i] = f.albedo[i] * (left ? 1.0f : 0.2f);
      if (byNormal) f.normal[i] = left ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
      if (!byNormal) f.depth[i] = left ? 2.0f : 6.0f;
    }
  const Frame noiseless = f;
  addIrradianceNoise(f, 0.1f, 2);
  const auto out = denoise(f, geometryOnly());
  for (uint32_t x : {f.width / 2 - 1, f.width / 2}) {
    double sum = 0;
    for (uint32_t y = 0; y < f.height; ++y) sum += out[f.at(x, y)].g;
    // A blur across would move these columns by a third of the step (0.4 * 0.5 / 3).
    EXPECT_NEAR(sum / f.height, noiseless.mean[f.at(x, 0)].g, 0.02) << "column " << x;
  }
}

INSTANTIATE_TEST_SUITE_P(NormalOrDepth, DenoiserGeometryEdge, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "Normal" : "Depth"; });

TEST_F(DenoiserFixture, NoiseOfKnownVarianceIsReducedByTheKernelsFactor) {
  // Three iterations (steps 1, 2, 4: 29 taps wide): many independent outputs in the interior, so the measured
  // variance is close to its expectation.
  const uint32_t iterations = 3, size = 128, border = 14;
  const float sigma = 0.2f;
  double sum2 = 0;
  size_t count = 0;
  for (uint32_t seed = 0; seed < 4; ++seed) {
    Frame f(size, size, 4.0f);
    addIrradianceNoise(f, sigma, 10 + seed);
    const auto out = denoise(f, geometryOnly(iterations));
    for (uint32_t y = border; y < size - border; ++y)
      for (uint32_t x = border; x < size - border; ++x)
        for (int c = 0; c < 3; ++c) {
          sum2 += std::pow(double(out[f.at(x, y)][c]) - 0.5, 2.0);
          ++count;
        }
  }
  const double inputVariance = double(sigma) * sigma * 0.25;  // albedo 0.5
  const double ratio = sum2 / double(count) / inputVariance, expected = expectedVarianceFactor(iterations);
  EXPECT_NEAR(ratio / expected, 1.0, 0.2) << "measured " << ratio << ", expected " << expected;
  EXPECT_LT(expectedVarianceFactor(5), expected) << "more iterations reduce more";
}

TEST_F(DenoiserFixture, HandsOverToTheRawImageAsTheMeanBecomesPrecise) {
  // A pattern no guide shows (a checkerboard of 4-pixel cells, as texture under a flat albedo would be) with
  // the per-sample variance of a noisy pixel: at few samples the filter smooths it, at many it leaves the raw
  // image.
  auto deviation = [&](float samples, const render::DenoiseOptions& options) {
    Frame f(48, 48, samples);
    for (uint32_t y = 0; y < f.height; ++y)
      for (uint32_t x = 0; x < f.width; ++x) {
        const size_t i = f.at(x, y);
        f.mean[i] = f.albedo[i] * ((((x / 4) + (y / 4)) % 2) ? 1.2f : 0.8f);
        f.meanVariance[i] = 0.25f / samples;  // per sample: 0.25
      }
    const auto out = denoise(f, options);
    double worst = 0;
    for (size_t i = 0; i < out.size(); ++i)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(out[i][c]) / f.mean[i][c] - 1.0));
    return worst;
  };
  // Both with the luminance edge-stopping (whose reach shrinks with the mean's variance) and without it (the
  // hand-over alone then makes the output the raw mean).
  render::DenoiseOptions noLuminance;
  noLuminance.sigmaLuminance = 0.0f;
  for (const auto& options : {render::DenoiseOptions{}, noLuminance}) {
    SCOPED_TRACE(options.sigmaLuminance);
    const double few = deviation(2.0f, options), some = deviation(256.0f, options),
                 many = deviation(1 << 20, options);
    EXPECT_GT(few, 0.05) << "at 2 samples the filter acts";
    EXPECT_LT(some, few);
    EXPECT_LT(many, some);
    EXPECT_LT(many, 1e-3) << "at 2^20 samples the output is the raw mean";
  }
}

// A real render (the default scene at 32x32): at many samples the denoised image equals the raw one within a
// small fraction of the raw image's own noise, and their means agree within 0.3%.
TEST(DenoiserRender, AtManySamplesTheDenoisedImageIsTheRawOneWithinItsNoise) {
  render::SessionOptions o;
  o.settings.width = 32;
  o.settings.height = 32;
  o.settings.denoise = true;
  o.settings.maxBounces = 4;
  auto session = wb::testing::makeSession(o);
  auto& tracer = session->pathTracer();
  session->render(1024);
  const auto raw = tracer.readEstimate();
  tracer.denoise();
  const auto den = tracer.readDenoised();
  // The raw image's variance per pixel (of its mean), from the stats AOV: E[L^2] - E[L]^2 over the samples.
  const auto stats = tracer.readAov(render::Aov::Stats);
  double diff2 = 0, noise = 0, rawSum = 0, denSum = 0;
  const size_t n = size_t(raw.width) * raw.height;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 a(raw.pixels[4 * i], raw.pixels[4 * i + 1], raw.pixels[4 * i + 2]);
    const glm::vec3 b(den.pixels[4 * i], den.pixels[4 * i + 1], den.pixels[4 * i + 2]);
    const double la = luminance(a), lb = luminance(b);
    diff2 += (la - lb) * (la - lb);
    noise += std::max(0.0, double(stats[4 * i]) - la * la) / 1024.0;
    rawSum += la;
    denSum += lb;
  }
  ASSERT_GT(noise, 0.0) << "the scene has noise at 1024 spp";
  EXPECT_LT(diff2, 0.25 * noise) << "the denoised image moves less than a quarter of the raw variance";
  // The filter darkens a little where bright outliers are not gathered back; at 1024 spp that is ~0.15%.
  EXPECT_NEAR(denSum / rawSum, 1.0, 3e-3) << "means within 0.3%";
  wb::testing::expectNoValidationErrors(*session);
}

// A denoised image's read times the denoiser as a pass of its own: `render --denoise --stats` has
// pass_ms.denoise beside pass_ms.pathtracer.
TEST(DenoiserRender, TheDenoisedImagesReadTimesTheDenoiser) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 32;
  o.settings.denoise = true;
  auto session = wb::testing::makeSession(o);
  vk::GpuTimer* timer = session->renderer().passTimer();
  ASSERT_NE(timer, nullptr);
  if (!timer->supported()) GTEST_SKIP() << "the queue writes no timestamps";
  session->render(2);
  const auto image = session->image();
  std::map<std::string, double> ms;
  for (const auto& t : timer->medians()) ms[t.pass] = t.ms;
  ASSERT_TRUE(ms.count("pathtracer") && ms.count("denoise")) << ms.size();
  EXPECT_GT(ms["denoise"], 0.0);
  EXPECT_EQ(image.width, 32u);
  wb::testing::expectNoValidationErrors(*session);
}
