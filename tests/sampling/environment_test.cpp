// Tests of src/sampling/environment.* and shaders/shared/env_sampling.h.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "common/paths.h"
#include "sampling/environment.h"
#include "shared/env_sampling.h"
#include "stats.h"

namespace wb {
namespace {

using glm::vec3;

std::filesystem::path gardenPath() {
  return sharedDir() / "assets" / "env" / "chinese_garden_1k.hdr";
}

struct BindEnv {
  explicit BindEnv(const EnvironmentMap& env) { gpu::gEnvAlias = env.alias.data(); }
  ~BindEnv() { gpu::gEnvAlias = nullptr; }
};

EnvironmentMap sunMap() {
  EnvironmentMap env;
  env.width = 64;
  env.height = 32;
  env.rgb.assign(64 * 32 * 3, 0.2f);
  for (int i = 0; i < 64 * 10; ++i) env.rgb[3 * i + 2] = 0.6f;  // bluish sky rows
  size_t sun = 7 * 64 + 40;
  env.rgb[3 * sun] = env.rgb[3 * sun + 1] = env.rgb[3 * sun + 2] = 0.2f * 1e5f;
  buildEnvironmentSampling(env);
  return env;
}

TEST(AliasTable, ExactProbabilities) {
  std::vector<double> w = {1.0, 0.0, 3.0, 0.5, 10.0, 2.5};
  auto t = buildAliasTable(w);
  // Probability of each outcome from the table equals weight / sum.
  std::vector<double> p(w.size(), 0.0);
  for (size_t i = 0; i < t.size(); ++i) {
    p[i] += t[i].prob / static_cast<double>(t.size());
    p[t[i].alias] += (1.0 - t[i].prob) / static_cast<double>(t.size());
  }
  for (size_t i = 0; i < w.size(); ++i) {
    EXPECT_NEAR(p[i], w[i] / 17.0, 1e-6) << i;
    EXPECT_NEAR(t[i].pdf, w[i] / 17.0, 1e-7) << i;
  }
  EXPECT_THROW(buildAliasTable({}), std::invalid_argument);
  EXPECT_THROW(buildAliasTable({0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(buildAliasTable({1.0, -1.0}), std::invalid_argument);
}

void chiSquarePixels(const EnvironmentMap& env, float rotation, uint32_t seed, const char* what) {
  BindEnv bind(env);
  const uint32_t w = env.width, h = env.height;
  const int n = 1000000;
  std::vector<double> obs(w * h, 0.0), exp(w * h, 0.0);
  test::Rng rng(seed);
  int invalid = 0;
  for (int i = 0; i < n; ++i) {
    gpu::EnvSample s = gpu::envSample(rng.next3(), w, h, rotation);
    ASSERT_TRUE(test::finite3(s.dir) && std::isfinite(s.pdf));
    if (!(s.pdf > 0.0f)) {
      ++invalid;
      continue;
    }
    ASSERT_EQ(s.pdf, gpu::envPdf(s.dir, w, h, rotation));
    glm::vec2 uv = gpu::directionToEquirect(s.dir, rotation);
    uint32_t x = std::min(static_cast<uint32_t>(uv.x * w), w - 1),
             y = std::min(static_cast<uint32_t>(uv.y * h), h - 1);
    obs[y * w + x] += 1.0;
  }
  for (size_t i = 0; i < exp.size(); ++i) exp[i] = env.alias[i].pdf * static_cast<double>(n);
  auto r = test::chiSquareTest(obs, exp);
  std::printf("env pixels %s: invalid=%d %s\n", what, invalid, r.describe().c_str());
  EXPECT_LT(invalid, 5);
  EXPECT_GT(r.pValue, 0.01) << what << ": " << r.describe();
}

void chiSquareDirections(const EnvironmentMap& env, float rotation, uint32_t seed, const char* what,
                         int sub) {
  BindEnv bind(env);
  const uint32_t w = env.width, h = env.height;
  const int n = 1000000;
  // Bin in world (cos theta about +Z, phi): axes unrelated to the map's, so the pdf formula itself is tested.
  test::SphereGrid grid{40, 80, -1.0};
  std::vector<double> obs(grid.size(), 0.0);
  test::Rng rng(seed);
  for (int i = 0; i < n; ++i) {
    gpu::EnvSample s = gpu::envSample(rng.next3(), w, h, rotation);
    if (s.pdf > 0.0f) obs[grid.index(s.dir)] += 1.0;
  }
  auto exp = grid.integrate([&](const vec3& d) { return gpu::envPdf(d, w, h, rotation); }, sub, n);
  double total = 0.0;
  for (double e : exp) total += e;
  auto r = test::chiSquareTest(obs, exp);
  std::printf("env directions %s: integral of pdf %.5f, %s\n", what, total / n, r.describe().c_str());
  EXPECT_NEAR(total / n, 1.0, 3e-3);
  EXPECT_GT(r.pValue, 0.01) << what << ": " << r.describe();
}

TEST(EnvironmentSampling, GardenMap) {
  EnvironmentMap env = loadHdrEnvironment(gardenPath());
  ASSERT_EQ(env.width, 1024);
  ASSERT_EQ(env.height, 512);
  EXPECT_GT(env.totalWeight, 0.0f);
  chiSquarePixels(env, 0.0f, 1, "garden");
  chiSquarePixels(env, 0.7f, 2, "garden rot 0.7");
  // Integral of the solid-angle pdf: per pixel, midpoint quadrature in (theta, phi) with 2x2 points.
  BindEnv bind(env);
  double integral = 0.0;
  const int w = env.width * 2, h = env.height * 2;
  for (int y = 0; y < h; ++y) {
    double theta = (y + 0.5) / h * std::numbers::pi;
    double ring = 0.0;
    for (int x = 0; x < w; ++x) {
      double phi = (x + 0.5) / w * 2.0 * std::numbers::pi;
      vec3 d(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
             static_cast<float>(std::sin(theta) * std::sin(phi)));
      ring += gpu::envPdf(d, env.width, env.height, 0.7f);
    }
    integral += ring * std::sin(theta) * (std::numbers::pi / h) * (2.0 * std::numbers::pi / w);
  }
  std::printf("garden: integral of envPdf %.5f\n", integral);
  EXPECT_NEAR(integral, 1.0, 5e-3);
}

TEST(EnvironmentSampling, SunMap) {
  EnvironmentMap env = sunMap();
  chiSquarePixels(env, 0.0f, 3, "sun");
  chiSquarePixels(env, -2.0f, 4, "sun rotated");
  // The sun's pdf dominates: nearly every sample lands in its pixel.
  BindEnv bind(env);
  test::Rng rng(5);
  int inSun = 0;
  for (int i = 0; i < 100000; ++i) {
    gpu::EnvSample s = gpu::envSample(rng.next3(), 64, 32, 0.0f);
    glm::vec2 uv = gpu::directionToEquirect(s.dir, 0.0f);
    inSun += (static_cast<int>(uv.y * 32) == 7 && static_cast<int>(uv.x * 64) == 40) ? 1 : 0;
  }
  EXPECT_NEAR(inSun / 1e5, env.alias[7 * 64 + 40].pdf, 0.005);
  // Integral of the solid-angle pdf over the sphere, by quadrature in (theta, phi) per pixel row.
  double integral = 0.0;
  const int sub = 64;
  for (int y = 0; y < 32 * sub; ++y) {
    double theta = (y + 0.5) / (32.0 * sub) * std::numbers::pi;
    for (int x = 0; x < 64 * 4; ++x) {
      double phi = (x + 0.5) / (64.0 * 4) * 2.0 * std::numbers::pi;
      vec3 d(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
             static_cast<float>(std::sin(theta) * std::sin(phi)));
      integral += gpu::envPdf(d, 64, 32, 0.3f) * std::sin(theta) * (std::numbers::pi / (32.0 * sub)) *
                  (2.0 * std::numbers::pi / (64.0 * 4));
    }
  }
  EXPECT_NEAR(integral, 1.0, 1e-2);
}

TEST(EnvironmentSampling, SmoothMapDirections) {
  // World-space (cos theta, phi) chi-square against quadrature of envPdf: checks the solid-angle pdf formula
  // and the rotation. A smooth 10:1 sky so the quadrature of the per-pixel constant pdf is accurate.
  EnvironmentMap env;
  env.width = 32;
  env.height = 16;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 32; ++x) {
      float v = 1.0f + 9.0f * (1.0f - y / 15.0f) * (0.5f + 0.5f * std::cos(x / 32.0f * 6.2831853f));
      env.rgb.insert(env.rgb.end(), {v, v * 0.9f, v * 0.8f});
    }
  }
  buildEnvironmentSampling(env);
  chiSquareDirections(env, 0.7f, 8, "smooth sky rot 0.7", 16);
}

TEST(EnvironmentSampling, ConstantMap) {
  EnvironmentMap env = constantEnvironment(vec3(0.5f, 0.6f, 0.7f));
  ASSERT_EQ(env.width, 1);
  ASSERT_EQ(env.alias.size(), 1u);
  EXPECT_FLOAT_EQ(env.alias[0].pdf, 1.0f);
  chiSquareDirections(env, 0.0f, 9, "constant", 6);
  EnvironmentMap black = constantEnvironment(vec3(0.0f));
  EXPECT_EQ(black.totalWeight, 0.0f);
  EXPECT_FLOAT_EQ(black.alias[0].pdf, 1.0f);
}

TEST(EnvironmentLoading, BadFilesThrowClearErrors) {
  try {
    loadHdrEnvironment("/nonexistent/env.hdr");
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/env.hdr"), std::string::npos) << e.what();
  }
  auto tmp = std::filesystem::temp_directory_path() / "wb_sampling_garbage.hdr";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << "#?RADIANCE\nthis is not an image";
  }
  try {
    loadHdrEnvironment(tmp);
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot decode"), std::string::npos) << e.what();
  }
  std::filesystem::remove(tmp);
}

}  // namespace
}  // namespace wb
