// Google Benchmark micro-benchmarks of the host-side hot spots (not tests; the performance suite of whole
// renders is `workbench bench`): the shaders' sampling and BRDF code compiled as C++, the environment's alias
// table, the shader library's compile and cache paths, and the SBT arithmetic.
// Run: build/micro_benchmarks [--benchmark_filter=REGEX]
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <vector>

#include "common/paths.h"
#include "sampling/blue_noise.h"
#include "sampling/environment.h"
#include "sampling/sobol.h"
#include "shader/library.h"
#include "shared/brdf.h"
#include "shared/random.h"
#include "vk/sbt.h"

namespace {

struct SamplerTables {
  std::vector<uint32_t> sobol = wb::sobolDirectionNumbers(static_cast<int>(WB_SOBOL_DIMS));
  std::vector<uint32_t> blue = wb::blueNoise128();
  SamplerTables() {
    wb::gpu::gSobolDirections = sobol.data();
    wb::gpu::gBlueNoise = blue.data();
  }
};

const SamplerTables& tables() {
  static const SamplerTables t;
  return t;
}

void BM_SobolSample(benchmark::State& state) {
  tables();
  uint32_t i = 0;
  float sum = 0;
  for (auto _ : state) {
    sum += wb::gpu::sobolSample(i, i & 31u);
    ++i;
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_SobolSample);

void BM_PcgHash(benchmark::State& state) {
  uint32_t v = 1;
  for (auto _ : state) {
    v = wb::gpu::pcgHash(v);
    benchmark::DoNotOptimize(v);
  }
}
BENCHMARK(BM_PcgHash);

void BM_BrdfSampleAndEval(benchmark::State& state) {
  using namespace wb::gpu;
  const SurfaceMaterial m = makeSurfaceMaterial(vec3(0.8f, 0.6f, 0.4f), 0.5f, float(state.range(0)) / 100.0f);
  const vec3 n(0.0f, 0.0f, 1.0f), wo = glm::normalize(vec3(0.3f, 0.2f, 0.9f));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (auto _ : state) {
    const BrdfSample s = brdfSample(m, n, wo, vec3(u(rng), u(rng), u(rng)));
    benchmark::DoNotOptimize(brdfEval(m, n, wo, s.wi));
  }
}
BENCHMARK(BM_BrdfSampleAndEval)->Arg(5)->Arg(50)->Arg(100);

void BM_EnvironmentAliasTable(benchmark::State& state) {
  const int w = int(state.range(0)), h = w / 2;
  std::vector<float> rgb(size_t(w) * h * 3);
  std::mt19937 rng(2);
  std::exponential_distribution<float> radiance(1.0f);
  for (float& v : rgb) v = radiance(rng);
  for (auto _ : state) {
    const auto weights = wb::environmentWeights(w, h, rgb);
    benchmark::DoNotOptimize(wb::buildAliasTable(weights));
  }
}
BENCHMARK(BM_EnvironmentAliasTable)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

// The path tracer's closest-hit shader: a glslang compile (cache off) and a load from the SPIR-V disk cache.
void BM_ShaderCompile(benchmark::State& state) {
  const bool cached = state.range(0) != 0;
  const auto cacheDir = std::filesystem::temp_directory_path() / "wb_micro_benchmarks_cache";
  wb::shader::ShaderLibrary::Options o;
  o.includeRoots = {wb::shaderDir()};
  o.cacheDir = cached ? cacheDir : std::filesystem::path();
  o.printWarnings = false;
  const wb::shader::ShaderKey key{wb::shaderDir() / "pathtracer" / "closesthit.rchit"};
  if (cached) wb::shader::ShaderLibrary(o).compile(key);  // fills the cache
  for (auto _ : state) {
    wb::shader::ShaderLibrary lib(o);  // a fresh library: nothing in memory
    benchmark::DoNotOptimize(lib.compile(key));
  }
  std::filesystem::remove_all(cacheDir);
}
BENCHMARK(BM_ShaderCompile)->Arg(0)->Arg(1)->ArgNames({"cached"})->Unit(benchmark::kMillisecond);

void BM_SbtLayout(benchmark::State& state) {
  uint32_t hit = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(wb::vk::computeSbtLayout(32, 16, 64, 2, hit, 0));
    hit = hit % 64 + 1;
  }
}
BENCHMARK(BM_SbtLayout);

}  // namespace

BENCHMARK_MAIN();
