#include "pt_helpers.h"

#include <stdexcept>

#include <unistd.h>

#include "stb_image_write.h"

namespace wb::testing {

Estimate estimateMean(render::RenderSession& session, render::RenderSettings settings, int batches,
                      uint32_t spp, uint32_t seedBase, render::SamplerKind sampler) {
  settings.sampler = sampler;
  const size_t pixels = size_t(settings.width) * settings.height;
  std::vector<double> sum(pixels, 0.0), sum2(pixels, 0.0);
  double batchSum = 0, batchSum2 = 0;  // of each render's image mean
  Estimate e;
  for (int k = 0; k < batches; ++k) {
    settings.seed = seedBase + uint32_t(k);
    session.pathTracer().setSettings(settings);
    session.render(spp);
    e.dropped += session.pathTracer().readCounters().droppedSamples;
    const auto img = session.image();
    double batchMean = 0;
    for (size_t p = 0; p < pixels; ++p) {
      double v = 0;
      for (int c = 0; c < 3; ++c) {
        const float x = img.pixels[4 * p + c];
        if (!std::isfinite(x)) e.nonFinite++;
        v += std::isfinite(x) ? x / 3.0 : 0.0;
      }
      sum[p] += v;
      sum2[p] += v * v;
      batchMean += v / double(pixels);
    }
    batchSum += batchMean;
    batchSum2 += batchMean * batchMean;
  }
  double total = 0, varSum = 0;
  for (size_t p = 0; p < pixels; ++p) {
    total += sum[p];
    varSum += std::max(0.0, (sum2[p] - sum[p] * sum[p] / batches) / (batches - 1));
  }
  e.mean = total / (double(pixels) * batches);
  // The sum of the pixels' variances is the image mean's when pixels are independent; the spread of the
  // renders' image means holds also where they are not (pixels that share a random choice: the reflector
  // guiding's coherent tiles). The larger of the two.
  const double pixelSigma = std::sqrt(varSum / batches) / double(pixels);
  const double batchVar =
      batches > 1 ? std::max(0.0, (batchSum2 - batchSum * batchSum / batches) / (batches - 1)) : 0.0;
  e.sigma = std::max(pixelSigma, std::sqrt(batchVar / batches));
  return e;
}

std::filesystem::path writeHdr(const std::string& name, int width, int height,
                               const std::vector<float>& rgb) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("wb_pt_test_" + std::to_string(::getpid()) + "_" + name + ".hdr");
  if (!stbi_write_hdr(path.string().c_str(), width, height, 3, rgb.data())) {
    throw std::runtime_error("cannot write " + path.string());
  }
  return path;
}

double imageMean(const eval::ImageRGBA& img) {
  double s = 0;
  const size_t n = size_t(img.width) * img.height;
  for (size_t i = 0; i < n; ++i)
    s += (img.pixels[4 * i] + img.pixels[4 * i + 1] + img.pixels[4 * i + 2]) / 3.0;
  return s / double(n);
}

}  // namespace wb::testing
