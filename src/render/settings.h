// Every path tracer parameter, as the command line, the UI and the tests set it.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <glm/glm.hpp>

namespace wb::render {

// Sobol: Sobol + blue-noise Cranley-Patterson rotation; Pcg: independent hashed numbers; Owen: Owen-scrambled
// Sobol sets (shaders/shared/random.h).
enum class SamplerKind { Sobol, Pcg, Owen };
// Their names, indexed by SamplerKind ("sobol", "pcg", "owen").
const std::vector<std::string>& samplerNames();
const char* samplerName(SamplerKind k);

// The path tracer, or one of its fast, biased counterparts.
enum class RenderMode { PathTrace, Hybrid, Reflections };
const char* renderModeName(RenderMode m);                            // "pathtrace" | "hybrid" | "reflections"
std::optional<RenderMode> parseRenderMode(const std::string& text);  // nullopt when unknown

struct RenderSettings {
  uint32_t width = 512, height = 512;
  uint32_t spp = 16;
  uint32_t maxBounces = 8;
  // First bounce at which Russian roulette may end a path, bounce 0 being the camera ray's hit (the numbering
  // of docs/path_inspector.md; the defaults' choice: docs/reports/error_per_sample.md).
  uint32_t rrStart = 2;
  float rrMin = 0.05f, rrMax = 0.95f;
  // Survival probability = clamp(max throughput component ^ rrExponent, rrMin, rrMax): 1 is proportional to
  // the throughput, 0.5 its square root (Cycles), which ends paths later for less variance per sample.
  float rrExponent = 0.5f;
  bool russianRoulette = true;
  bool nee = true;  // next-event estimation (lights + environment)
  bool mis = true;  // MIS between environment NEE and BRDF sampling (off: light sampling only)
  SamplerKind sampler = SamplerKind::Owen;
  uint32_t seed = 0;
  bool aov = false;  // albedo + normal AOVs
  // The path tracer's image is denoised (render/denoiser.h; the AOVs are written for it): what readImage()
  // returns and the window shows. The accumulation itself, the inspector and A/B stay raw.
  bool denoise = false;
  uint32_t debugView = 0;
  // Dispatch shape of a headless sample: tiles of this size (0 = the whole image in one vkCmdTraceRaysKHR).
  uint32_t tileWidth = 0, tileHeight = 0;
  // Samples traced by one launch of a whole-image sample (launch depth; a resolve pass accumulates them in
  // order, the image is the same): 0 = the device policy's choice (PathTracer::samplesPerLaunch: 1 on a CPU
  // device, enough to fill a GPU at small sizes).
  uint32_t samplesPerLaunch = 0;
  bool generic = false;  // the all-features shader build instead of the scene-specialised one
  // Extra preprocessor defines for the path tracer's stages (`--define K=V`): shader experiments from the
  // command line; part of the variant key like the scene's features.
  std::vector<std::pair<std::string, std::string>> defines;

  // Environment: an equirectangular .hdr, or a constant colour.
  std::string envPath;
  glm::vec3 envColor{0.4f, 0.45f, 0.5f};
  float envRotationDeg = 0.0f;
  float envIntensity = 1.0f;
  // The directional lights' angular diameter in degrees, in every mode (`--sun-angle`, scene::withSunAngle):
  // 0 makes them delta lights, a negative value keeps the scene's (glTF lights are delta lights).
  float sunAngleDeg = -1.0f;

  bool operator==(const RenderSettings&) const = default;
};

}  // namespace wb::render
