// The denoiser (render/denoiser.h) on analytic images uploaded as the path tracer's images would be: a flat
// image stays flat, an edge in albedo, normal or depth is kept, noise of known variance is reduced by the
// factor the a-trous kernel predicts, the output hands over to the raw mean as the samples grow (consistency
// by construction), and on a real render at many samples the denoised image is the raw one within its noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

float halfToFloat(uint16_t h) {
  // The inverse of floatToHalf on what it makes: zero and the normal range.
  const uint32_t sign = uint32_t(h & 0x8000u) << 16, exponent = (h >> 10) & 0x1fu, mantissa = h & 0x3ffu;
  const uint32_t x = exponent == 0 ? sign : sign | ((exponent - 15 + 127) << 23) | (mantissa << 13);
  float f;
  std::memcpy(&f, &x, 4);
  return f;
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

  // Uploads the frame as the path tracer's images, runs the denoiser (filtering rows [0, rows)) and reads its
  // output (rgb per pixel).
  std::vector<glm::vec3> denoise(const Frame& f, const render::DenoiseOptions& options, uint32_t rows = ~0u) {
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
    ctx->submitAndWait([&](VkCommandBuffer cmd) { denoiser->record(cmd, rows); });
    const auto out = denoiser->readOutput();
    std::vector<glm::vec3> rgb(count);
    for (size_t i = 0; i < count; ++i) {
      rgb[i] = {out[4 * i], out[4 * i + 1], out[4 * i + 2]};
      EXPECT_EQ(out[4 * i + 3], f.samples[i]) << "alpha carries the samples per pixel";
    }
    return rgb;
  }
};

// The filter alone: no luminance edge-stopping, no hand-over, no windowed gain (what the geometry and the
// albedo keep).
render::DenoiseOptions geometryOnly(uint32_t iterations = 5) {
  render::DenoiseOptions o;
  o.iterations = iterations;
  o.sigmaLuminance = 0.0f;
  o.handoverTau = -1.0f;
  o.window = false;
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

// The variance reduction of the linear a-trous filter (its 3-tap kernel, steps 1, 2, 4, ...) away from the
// borders: the sum of the squared weights of the composed 2D kernel (separable: the square of the 1D sum).
double expectedVarianceFactor(uint32_t iterations) {
  const double kernel[3] = {WB_DENOISE_KERNEL_SIDE, WB_DENOISE_KERNEL_CENTER, WB_DENOISE_KERNEL_SIDE};
  std::vector<double> k{1.0};
  for (uint32_t i = 0; i < iterations; ++i) {
    const size_t step = size_t(1) << i;
    std::vector<double> next(k.size() + 2 * step, 0.0);
    for (size_t a = 0; a < k.size(); ++a)
      for (size_t t = 0; t < 3; ++t) next[a + t * step] += k[a] * kernel[t];
    k = std::move(next);
  }
  double sum2 = 0;
  for (double w : k) sum2 += w * w;
  return sum2 * sum2;
}

// The denoiser's math on the CPU, written from the shaders' definitions one pass at a time (prepare,
// variance, the a-trous iterations, final) with the straightforward loops: what the GPU passes compute,
// however they are arranged for speed. rgb per pixel; rows [0, rows) filtered, the others the raw mean.
class ReferenceDenoiser {
 public:
  ReferenceDenoiser(const Frame& f, const render::DenoiseOptions& o, uint32_t rows)
      : f_(f), o_(o), w_(int(f.width)), h_(int(f.height)), rows_(int(std::min(rows, f.height))) {}

  std::vector<glm::vec3> run() {
    const size_t count = size_t(w_) * h_;
    ping_.assign(count, glm::vec4(0));
    guide_.assign(count, glm::vec4(0));
    gradient_.assign(count, 0.0f);
    variance_.assign(count, 0.0f);
    prepare();
    std::vector<glm::vec4> filtered = varianceOfMean();
    for (uint32_t i = 0; i < o_.iterations; ++i) filtered = atrous(filtered, 1 << i);
    const auto out = final(filtered);
    return o_.window ? windowGain(out) : out;
  }

 private:
  // The inputs as the GPU reads them: albedo, normal and depth through half floats, the stats' mean of
  // luminance^2 as the fixture uploads it.
  glm::vec3 albedo(int i) const {
    return {halfToFloat(floatToHalf(f_.albedo[i].x)), halfToFloat(floatToHalf(f_.albedo[i].y)),
            halfToFloat(floatToHalf(f_.albedo[i].z))};
  }
  glm::vec3 normal(int i) const {
    return {halfToFloat(floatToHalf(f_.normal[i].x)), halfToFloat(floatToHalf(f_.normal[i].y)),
            halfToFloat(floatToHalf(f_.normal[i].z))};
  }
  float depth(int i) const { return halfToFloat(floatToHalf(f_.depth[i])); }
  float lum2(int i) const {
    const float n = f_.samples[i], lum = luminance(f_.mean[i]), perSample = f_.meanVariance[i] * n;
    return lum * lum + (n > 1.0f ? perSample * (n - 1.0f) / n : 0.0f);
  }
  static glm::vec3 demodulationAlbedo(glm::vec3 a) {
    return std::max(a.r, std::max(a.g, a.b)) < 0.02f ? glm::vec3(1.0f) : glm::max(a, glm::vec3(0.02f));
  }
  static glm::vec3 unitNormal(glm::vec3 n) {
    return glm::dot(n, n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f);
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w_ && y < rows_; }
  int at(int x, int y) const { return y * w_ + x; }

  float normalWeight(glm::vec3 nP, glm::vec3 nQ) const {
    const float c = std::max(glm::dot(nP, nQ), 0.0f);
    return std::pow(c, o_.sigmaNormal);
  }
  float depthExponent(int p, int q, float distance) const {
    const float expected = o_.sigmaDepth * gradient_[p] * distance + 1.0e-3f * guide_[p].w;
    return std::abs(guide_[p].w - guide_[q].w) / expected;
  }
  float geometryWeight(int p, int q, float distance) const {
    const bool missP = guide_[p].w < 0.0f, missQ = guide_[q].w < 0.0f;
    if (missP || missQ) return missP && missQ ? 1.0f : 0.0f;
    return normalWeight(glm::vec3(guide_[p]), glm::vec3(guide_[q])) *
           std::exp(-depthExponent(p, q, distance));
  }
  static float kernelWeight(int i) {
    return float(i == 0 ? WB_DENOISE_KERNEL_CENTER : WB_DENOISE_KERNEL_SIDE);
  }
  static float median9(std::array<float, 9> v) {
    std::sort(v.begin(), v.end());
    return v[4];
  }

  void prepare() {
    for (int y = 0; y < rows_; ++y)
      for (int x = 0; x < w_; ++x) {
        const int i = at(x, y);
        const glm::vec3 a = demodulationAlbedo(albedo(i)), demodulated = f_.mean[i] / a;
        const float n = f_.samples[i];
        float variance = -1.0f;
        if (n >= 2.0f) {
          const float lum = luminance(f_.mean[i]), lumD = luminance(demodulated);
          const float scale = lum > 0.0f && lumD > 0.0f ? lumD / lum : 1.0f / luminance(a);
          variance = std::max(lum2(i) - lum * lum, 0.0f) * n / (n - 1.0f) * scale * scale;
        }
        ping_[i] = glm::vec4(demodulated, variance);
        const float z = depth(i);
        auto depthAt = [&](int qx, int qy) { return inside(qx, qy) ? depth(at(qx, qy)) : 1.0e30f; };
        const float dx = std::min(std::abs(depthAt(x + 1, y) - z), std::abs(z - depthAt(x - 1, y)));
        const float dy = std::min(std::abs(depthAt(x, y + 1) - z), std::abs(z - depthAt(x, y - 1)));
        gradient_[i] = std::min(std::sqrt(dx * dx + dy * dy), std::abs(z));
        guide_[i] = glm::vec4(unitNormal(normal(i)), z);
      }
  }

  std::vector<glm::vec4> varianceOfMean() {
    std::vector<glm::vec4> out(ping_.size(), glm::vec4(0));
    for (int y = 0; y < rows_; ++y)
      for (int x = 0; x < w_; ++x) {
        const int p = at(x, y);
        const glm::vec4 center = ping_[p];
        const float n = f_.samples[p];
        const bool own = n >= 2.0f;
        const float self = own ? std::max(center.a, 0.0f) : luminance(glm::vec3(center));
        // The neighbour dx, dy of p when it is on p's surface, else -1.
        auto onSurface = [&](int dx, int dy) {
          if (!inside(x + dx, y + dy)) return -1;
          const int q = at(x + dx, y + dy);
          return geometryWeight(p, q, std::sqrt(float(dx * dx + dy * dy))) > float(WB_DENOISE_SAME_SURFACE)
                     ? q
                     : -1;
        };
        std::array<float, 9> v;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            float value = self;
            if (const int q = onSurface(dx, dy); q >= 0) {
              if (!own) {
                value = luminance(glm::vec3(ping_[q]));
              } else if (ping_[q].a >= 0.0f) {
                value = ping_[q].a;
              }
            }
            v[(dy + 1) * 3 + dx + 1] = value;
          }
        float variance = 0.0f;
        if (own) {
          variance = std::max(self, median9(v));
          if (n < float(WB_DENOISE_SHORT_HISTORY)) {
            std::array<float, 9> lum;
            const float lumP = luminance(glm::vec3(center));
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const int q = onSurface(dx, dy);
                lum[(dy + 1) * 3 + dx + 1] = q >= 0 ? luminance(glm::vec3(ping_[q])) : lumP;
              }
            const float m = median9(lum);
            for (float& e : lum) e = std::abs(e - m);
            const float spread = 1.4826f * median9(lum);
            variance = std::max(variance, n * spread * spread);
          }
        } else if (n > 0.0f) {
          const float m = median9(v);
          for (float& e : v) e = std::abs(e - m);
          const float spread = 1.4826f * median9(v);
          variance = std::max((self - m) * (self - m), spread * spread);
        }
        variance_[p] = n > 0.0f ? variance / n : 0.0f;
        out[p] = glm::vec4(glm::vec3(center), variance_[p]);
      }
    return out;
  }

  std::vector<glm::vec4> atrous(const std::vector<glm::vec4>& in, int step) const {
    std::vector<glm::vec4> out(in.size(), glm::vec4(0));
    for (int y = 0; y < rows_; ++y)
      for (int x = 0; x < w_; ++x) {
        const int p = at(x, y);
        const glm::vec4 center = in[p];
        const bool missP = guide_[p].w < 0.0f;
        const float lumP = luminance(glm::vec3(center));
        const float reach = 2.0f * o_.sigmaLuminance * o_.sigmaLuminance * std::max(center.a, 0.0f);
        const float center2 = kernelWeight(0) * kernelWeight(0);
        glm::vec3 sum = glm::vec3(center) * center2;
        float weights = center2, variance = center.a * center2 * center2;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || !inside(x + dx * step, y + dy * step)) continue;
            const int q = at(x + dx * step, y + dy * step);
            const glm::vec4 c = in[q];
            float w = kernelWeight(dx) * kernelWeight(dy), exponent = 0.0f;
            const bool missQ = guide_[q].w < 0.0f;
            if (missP || missQ) {
              if (missP != missQ) continue;
            } else {
              w *= normalWeight(glm::vec3(guide_[p]), glm::vec3(guide_[q]));
              exponent = depthExponent(p, q, float(step) * std::sqrt(float(dx * dx + dy * dy)));
            }
            if (o_.sigmaLuminance > 0.0f) {
              const float d = luminance(glm::vec3(c)) - lumP;
              exponent += reach > 0.0f ? d * d / reach : (d == 0.0f ? 0.0f : 1.0e30f);
            }
            w *= std::exp(-exponent);
            sum += w * glm::vec3(c);
            weights += w;
            variance += w * w * std::max(c.a, 0.0f);
          }
        out[p] = glm::vec4(sum / weights, variance / (weights * weights));
      }
    return out;
  }

  std::vector<glm::vec3> final(const std::vector<glm::vec4>& filtered) const {
    std::vector<glm::vec3> out(filtered.size());
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) {
        const int p = at(x, y);
        if (!inside(x, y)) {
          out[p] = f_.mean[p];
          continue;
        }
        const glm::vec3 denoised = glm::vec3(filtered[p]) * demodulationAlbedo(albedo(p));
        float a = 1.0f;
        if (o_.handoverTau >= 0.0f) {
          float difference2 = 0.0f, variance = 0.0f;
          int n = 0;
          for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
              if (!inside(x + dx, y + dy)) continue;
              const int q = at(x + dx, y + dy);
              const float raw = luminance(f_.mean[q] / demodulationAlbedo(albedo(q)));
              const float d = luminance(glm::vec3(filtered[q])) - raw;
              difference2 += d * d;
              variance += variance_[q];
              ++n;
            }
          const float bias2 = std::max(difference2 - variance, 0.0f) / float(std::max(n, 1));
          const float v = variance_[p], assumed = o_.handoverTau * luminance(glm::vec3(filtered[p]));
          const float total = v + std::max(filtered[p].a, 0.0f) + std::max(assumed * assumed, bias2);
          a = total > 0.0f ? v / total : 0.0f;
        }
        out[p] = f_.mean[p] + a * (denoised - f_.mean[p]);
      }
    return out;
  }

  // gain.comp and scale.comp: per group of final.comp, its deficit (raw - output) shared among the groups of
  // its window in proportion to their output; each pixel times its group's gain, interpolated between group
  // centres.
  std::vector<glm::vec3> windowGain(const std::vector<glm::vec3>& out) const {
    const int n = WB_DENOISE_GROUP_SIZE, gw = (w_ + n - 1) / n, gh = (h_ + n - 1) / n,
              r = WB_DENOISE_WINDOW_GROUPS;
    std::vector<glm::dvec3> raw(size_t(gw) * gh, glm::dvec3(0)), result(raw.size(), glm::dvec3(0));
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) {
        raw[size_t(y / n) * gw + x / n] += glm::dvec3(f_.mean[at(x, y)]);
        result[size_t(y / n) * gw + x / n] += glm::dvec3(out[at(x, y)]);
      }
    auto windowSum = [&](const std::vector<glm::dvec3>& v, int gx, int gy) {
      glm::dvec3 sum(0);
      for (int y = std::max(gy - r, 0); y <= std::min(gy + r, gh - 1); ++y)
        for (int x = std::max(gx - r, 0); x <= std::min(gx + r, gw - 1); ++x) sum += v[size_t(y) * gw + x];
      return sum;
    };
    std::vector<glm::dvec3> share(raw.size()), gain(raw.size());
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx) {
        const size_t g = size_t(gy) * gw + gx;
        const glm::dvec3 sum = windowSum(result, gx, gy);
        for (int c = 0; c < 3; ++c) share[g][c] = sum[c] > 0 ? (raw[g][c] - result[g][c]) / sum[c] : 0.0;
      }
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx)
        gain[size_t(gy) * gw + gx] = glm::max(glm::dvec3(1.0) + windowSum(share, gx, gy), glm::dvec3(0.0));
    auto gainAt = [&](int gx, int gy) {
      return gain[size_t(std::clamp(gy, 0, gh - 1)) * gw + std::clamp(gx, 0, gw - 1)];
    };
    std::vector<glm::vec3> scaled(out.size());
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) {
        const double ux = (x + 0.5) / n - 0.5, uy = (y + 0.5) / n - 0.5;
        const int gx = int(std::floor(ux)), gy = int(std::floor(uy));
        const double fx = ux - gx, fy = uy - gy;
        const glm::dvec3 g = (gainAt(gx, gy) * (1 - fx) + gainAt(gx + 1, gy) * fx) * (1 - fy) +
                             (gainAt(gx, gy + 1) * (1 - fx) + gainAt(gx + 1, gy + 1) * fx) * fy;
        scaled[at(x, y)] = glm::vec3(glm::dvec3(out[at(x, y)]) * g);
      }
    return scaled;
  }

  const Frame& f_;
  render::DenoiseOptions o_;
  int w_, h_, rows_;
  std::vector<glm::vec4> ping_, guide_;  // guide: the unit normal, depth
  std::vector<float> gradient_, variance_;
};

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

TEST_F(DenoiserFixture, ComputesWhatAReferenceOfItsMathOnTheCpuDoes) {
  // A scene-like frame: surfaces of several albedos, normals (some facing away from +z) and depth slopes, a
  // region of misses, an emitter, pixels of 1, 2 and 16 samples, noise; odd sizes, so that blocks and
  // workgroups overhang the image.
  Frame f(45, 37, 16.0f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (uint32_t y = 0; y < f.height; ++y)
    for (uint32_t x = 0; x < f.width; ++x) {
      const size_t i = f.at(x, y);
      const int region = int(x / 12 + 4 * (y / 10));
      f.albedo[i] = glm::vec3(0.2f + 0.15f * float(region % 5), 0.7f - 0.1f * float(region % 4), 0.5f);
      f.normal[i] =
          glm::normalize(glm::vec3(0.3f * float(region % 3) - 0.3f, 0.2f, region % 4 == 3 ? -1.0f : 1.0f));
      f.depth[i] = 2.0f + 0.05f * float(x) + 0.5f * float(region % 2) + 0.01f * float(y);
      const float irradiance = 0.5f + u(rng);
      f.mean[i] = f.albedo[i] * irradiance;
      f.meanVariance[i] = 0.01f + 0.05f * u(rng);
      f.samples[i] = x < 6 ? 1.0f : x < 10 ? 2.0f : 16.0f;
      if (x > 36 && y < 8) {  // a miss: no albedo, no normal, negative depth
        f.albedo[i] = glm::vec3(0.0f);
        f.normal[i] = glm::vec3(0.0f);
        f.depth[i] = -1.0f;
        f.mean[i] = glm::vec3(0.3f, 0.4f, 0.5f);
      }
      if (x >= 20 && x < 23 && y >= 20 && y < 23) {  // an emitter: black albedo, bright
        f.albedo[i] = glm::vec3(0.0f);
        f.mean[i] = glm::vec3(20.0f);
      }
    }
  render::DenoiseOptions pow64;
  pow64.sigmaNormal = 64.0f;  // pow() rather than squaring
  render::DenoiseOptions noHandover = geometryOnly();
  noHandover.sigmaLuminance = 4.0f;
  struct Case {
    const char* name;
    render::DenoiseOptions options;
    uint32_t rows;
  };
  render::DenoiseOptions noWindow;
  noWindow.window = false;
  for (const Case& c : {Case{"default", {}, ~0u}, Case{"no window", noWindow, ~0u},
                        Case{"sigmaNormal 64", pow64, ~0u}, Case{"geometry only", geometryOnly(), ~0u},
                        Case{"no hand-over", noHandover, ~0u}, Case{"rows [0, 21)", {}, 21u}}) {
    SCOPED_TRACE(c.name);
    const auto gpu = denoise(f, c.options, c.rows);
    const auto cpu = ReferenceDenoiser(f, c.options, c.rows).run();
    double worst = 0;
    for (size_t i = 0; i < gpu.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double scale = std::max(std::abs(double(cpu[i][k])), 1e-2);
        worst = std::max(worst, std::abs(double(gpu[i][k]) - cpu[i][k]) / scale);
        ASSERT_NEAR(gpu[i][k], cpu[i][k], 1e-4 * scale) << "pixel " << i % f.width << "," << i / f.width;
      }
    std::printf("[ %s ] largest relative difference to the CPU reference: %.3g\n", c.name, worst);
  }
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

// Two samples per pixel of a sparse irradiance (each sample 0 or 2, as where few paths find the light), on a
// surface facing the camera and on one slanted away from it (its depth changes by 0.05 per pixel on each axis
// and grows faster to the right and down, as under a perspective). The slanted surface is denoised about as
// well as the facing one: its pixels find their neighbours on the same surface for their variance estimates,
// and no pixel keeps the black of its two samples (a dark speck) more often than on the facing surface.
TEST_F(DenoiserFixture, ASlantedSurfaceIsDenoisedAsWellAsAFacingOne) {
  const uint32_t size = 64, border = 4;
  auto frame = [&](bool slanted) {
    Frame f(size, size, 2.0f);
    std::mt19937 rng(7);
    std::bernoulli_distribution lit(0.5);
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const size_t i = f.at(x, y);
        const float a = lit(rng) ? 2.0f : 0.0f, b = lit(rng) ? 2.0f : 0.0f;
        f.mean[i] = f.albedo[i] * (0.5f * (a + b));
        const float la = luminance(f.albedo[i] * a), lb = luminance(f.albedo[i] * b);
        f.meanVariance[i] = (la - lb) * (la - lb) / 4.0f;  // (a - b)^2 / 2 per sample, over 2 samples
        if (slanted) f.depth[i] = 2.0f + 0.05f * float(x + y) + 0.001f * float(x * x + y * y);
      }
    return f;
  };
  struct Result {
    double rmse = 0;
    size_t specks = 0;
  };
  auto measure = [&](bool slanted) {
    const Frame f = frame(slanted);
    const auto out = denoise(f, render::DenoiseOptions{});
    Result r;
    size_t count = 0;
    for (uint32_t y = border; y < size - border; ++y)
      for (uint32_t x = border; x < size - border; ++x) {
        const float l = luminance(out[f.at(x, y)]), truth = luminance(f.albedo[f.at(x, y)]);
        r.rmse += double(l - truth) * (l - truth);
        r.specks += l < 0.2f * truth;
        ++count;
      }
    r.rmse = std::sqrt(r.rmse / double(count));
    return r;
  };
  const Result facing = measure(false), slanted = measure(true);
  std::printf("facing: rmse %.4f, %zu specks; slanted: rmse %.4f, %zu specks\n", facing.rmse, facing.specks,
              slanted.rmse, slanted.specks);
  EXPECT_LT(slanted.rmse, 1.25 * facing.rmse);
  EXPECT_LE(slanted.specks, 2 * facing.specks + 5);
}

TEST_F(DenoiserFixture, NoiseOfKnownVarianceIsReducedByTheKernelsFactor) {
  // Three iterations (steps 1, 2, 4: 15 taps wide): many independent outputs in the interior, so the measured
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

// The windowed gain (DenoiseOptions::window): what the filter takes from fireflies goes back to their
// surroundings, across albedos, so the image's radiance is the raw one's; without it the filter loses most of
// the fireflies' energy. A flat image stays flat.
TEST_F(DenoiserFixture, TheWindowedGainKeepsTheImagesRadiance) {
  Frame f(72, 56, 16.0f);  // not a multiple of the 8x8 groups: partial groups at the right and bottom
  addIrradianceNoise(f, 0.1f, 7);
  for (uint32_t y = 0; y < f.height; ++y)
    for (uint32_t x = 0; x < f.width; ++x) {
      const size_t i = f.at(x, y);
      const float a = x < 30 ? 0.2f : 0.8f;  // one plane, two grey albedos
      f.mean[i] *= a / 0.5f;
      f.albedo[i] = glm::vec3(a);
      f.meanVariance[i] *= (a / 0.5f) * (a / 0.5f);
    }
  // One sample 2000x the mean, in the interior, next to the albedo edge and in a corner.
  for (const auto& [x, y] : {std::pair{18u, 12u}, std::pair{31u, 30u}, std::pair{70u, 54u}}) {
    const size_t i = f.at(x, y);
    const glm::vec3 firefly = f.mean[i] * (1.0f + 2000.0f / f.samples[i]);
    const float l = luminance(firefly - f.mean[i]);
    f.mean[i] = firefly;
    f.meanVariance[i] = l * l / f.samples[i];
  }
  auto total = [](const std::vector<glm::vec3>& image) {
    glm::dvec3 sum(0.0);
    for (const auto& v : image) sum += glm::dvec3(v);
    return sum;
  };
  const glm::dvec3 in = total(f.mean);
  render::DenoiseOptions window, without;
  without.window = false;
  const auto out = denoise(f, window);
  const auto lost = denoise(f, without);
  for (int c = 0; c < 3; ++c) {
    std::printf("channel %d: with the gain %.6f of the raw radiance, without %.6f\n", c,
                total(out)[c] / in[c], total(lost)[c] / in[c]);
    EXPECT_NEAR(total(out)[c] / in[c], 1.0, 2e-3) << "channel " << c;
    EXPECT_LT(total(lost)[c] / in[c], 0.98)
        << "without the gain the fireflies' energy is lost (channel " << c << ")";
  }
  const size_t firefly = f.at(18, 12);
  // The energy goes to the window, not back to the firefly: its pixel stays as the filter left it, within the
  // window's small gain.
  EXPECT_LT(luminance(out[firefly]), 0.5f * luminance(f.mean[firefly]));
  EXPECT_NEAR(luminance(out[firefly]) / luminance(lost[firefly]), 1.0, 0.25);
  Frame flat(40, 24, 8.0f);
  for (size_t i = 0; i < flat.mean.size(); ++i) flat.meanVariance[i] = 0.05f;
  const auto flatOut = denoise(flat, window);
  for (size_t i = 0; i < flatOut.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(flatOut[i][c], 0.5f, 1e-5f) << "pixel " << i;
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
// small fraction of the raw image's own noise, and their means agree within 0.3%. The estimator is pinned
// (reflector guiding off, the estimator the bound was measured on: with guiding the raw variance is lower and
// the filter's move measured 0.253 of it): the test is of the filter, on a fixed input.
TEST(DenoiserRender, AtManySamplesTheDenoisedImageIsTheRawOneWithinItsNoise) {
  render::SessionOptions o;
  o.settings.defines = {{"WB_REFLECTOR_GUIDING", "0"}};
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
