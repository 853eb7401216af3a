#include "sampling/environment.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/file_io.h"
#include "common/image_decode.h"

namespace wb {

std::vector<double> environmentWeights(int width, int height, const std::vector<float>& rgb) {
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (width <= 0 || height <= 0 || rgb.size() != n * 3) {
    throw std::invalid_argument("environmentWeights: size mismatch");
  }
  std::vector<double> w(n, 0.0);
  double sum = 0.0;
  for (int y = 0; y < height; ++y) {
    double sinTheta = std::sin((y + 0.5) / height * std::numbers::pi);
    for (int x = 0; x < width; ++x) {
      size_t i = static_cast<size_t>(y) * width + x;
      double lum = 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
      if (!std::isfinite(lum) || lum < 0.0) lum = 0.0;
      w[i] = lum * sinTheta;
      sum += w[i];
    }
  }
  if (!(sum > 0.0)) {
    for (int y = 0; y < height; ++y) {
      double sinTheta = std::sin((y + 0.5) / height * std::numbers::pi);
      for (int x = 0; x < width; ++x) w[static_cast<size_t>(y) * width + x] = sinTheta;
    }
  }
  return w;
}

std::vector<gpu::EnvAliasEntry> buildAliasTable(const std::vector<double>& weights) {
  const size_t n = weights.size();
  if (n == 0) throw std::invalid_argument("buildAliasTable: no weights");
  double sum = 0.0;
  for (double w : weights) {
    if (!(w >= 0.0) || !std::isfinite(w))
      throw std::invalid_argument("buildAliasTable: negative or non-finite weight");
    sum += w;
  }
  if (!(sum > 0.0)) throw std::invalid_argument("buildAliasTable: all weights are zero");
  std::vector<gpu::EnvAliasEntry> table(n);
  std::vector<double> scaled(n);
  std::vector<uint32_t> small;
  std::vector<uint32_t> large;
  small.reserve(n);
  large.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    table[i].pdf = static_cast<float>(weights[i] / sum);
    table[i].alias = static_cast<uint32_t>(i);
    table[i].prob = 1.0f;
    table[i].pad0 = 0.0f;
    scaled[i] = weights[i] / sum * static_cast<double>(n);
    (scaled[i] < 1.0 ? small : large).push_back(static_cast<uint32_t>(i));
  }
  while (!small.empty() && !large.empty()) {
    uint32_t s = small.back();
    small.pop_back();
    uint32_t l = large.back();
    table[s].prob = static_cast<float>(scaled[s]);
    table[s].alias = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Leftovers (round-off) keep themselves with probability 1.
  for (uint32_t i : small) table[i].prob = 1.0f;
  for (uint32_t i : large) table[i].prob = 1.0f;
  return table;
}

void buildEnvironmentSampling(EnvironmentMap& env) {
  std::vector<double> w = environmentWeights(env.width, env.height, env.rgb);
  // totalWeight is the luminance-weighted sum (0 for a black map, whose table falls back to sin(theta)
  // weights).
  double sum = 0.0;
  for (size_t i = 0; i < w.size(); ++i) {
    const float* c = &env.rgb[3 * i];
    double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    if (std::isfinite(lum) && lum > 0.0) sum += w[i];
  }
  env.alias = buildAliasTable(w);
  env.totalWeight = static_cast<float>(sum);
}

EnvironmentMap loadHdrEnvironment(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw std::runtime_error("environment " + name + ": is a directory, not an image file");
  if (!std::filesystem::exists(path, ec)) throw std::runtime_error("environment " + name + ": no such file");
  std::string why;
  const auto bytes = readRegularFile(path, &why);
  if (!bytes) throw std::runtime_error("environment " + name + ": cannot read (" + why + ")");
  const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
  const ImageFormat format = sniffImageFormat(data, bytes->size());
  if (format == ImageFormat::Unknown) {
    throw std::runtime_error("environment " + name +
                             ": not a Radiance .hdr, PNG or JPEG file (equirectangular .hdr expected)");
  }
  EnvironmentMap env;
  try {
    FloatImage img = decodeLinearRgb(data, bytes->size());
    env.width = int(img.width);
    env.height = int(img.height);
    env.rgb = std::move(img.rgb);
  } catch (const ImageDecodeError& e) {
    throw std::runtime_error("environment " + name + ": cannot decode image (" + e.what() + ")");
  }
  if (format != ImageFormat::RadianceHdr) {
    // An 8-bit image holds display values, not radiance: decoded from sRGB to linear, its brightest sky is 1.
    env.warnings.push_back("environment " + name + " is an 8-bit " + imageFormatName(format) +
                           " image, not HDR: decoded from sRGB to linear radiance of at most 1 "
                           "(--env-intensity scales it)");
  }
  if (env.width < 2 || env.height < 1) {
    throw std::runtime_error("environment " + name + ": image too small for an environment (" +
                             std::to_string(env.width) + "x" + std::to_string(env.height) + ")");
  }
  bool anyFinite = false;
  for (float& v : env.rgb) {
    if (std::isfinite(v)) {
      anyFinite = true;
      if (v < 0.0f) v = 0.0f;
    } else {
      v = 0.0f;  // NaN / Inf texels would poison every estimate: zero them
    }
  }
  if (!anyFinite) throw std::runtime_error("environment " + name + ": no finite pixels");
  buildEnvironmentSampling(env);
  return env;
}

EnvironmentMap constantEnvironment(glm::vec3 radiance) {
  EnvironmentMap env;
  env.width = 1;
  env.height = 1;
  env.rgb = {radiance.x, radiance.y, radiance.z};
  buildEnvironmentSampling(env);
  return env;
}

}  // namespace wb
