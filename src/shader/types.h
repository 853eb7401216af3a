// Value types of the shader library: stages, keys, diagnostics, reflection and compiled results.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wb::shader {

namespace fs = std::filesystem;

enum class Stage { Vertex, Fragment, Compute, RayGen, AnyHit, ClosestHit, Miss, Intersection, Callable };

VkShaderStageFlagBits toVkStage(Stage s);
const char* stageName(Stage s);  // "vert", "frag", "comp", "rgen", "rahit", "rchit", "rmiss", "rint", "rcall"
// .rgen .rmiss .rchit .rahit .rint .rcall .vert .frag .comp, also name.<stage>.glsl; nullopt otherwise.
std::optional<Stage> stageFromPath(const fs::path& p);
// "raygen|miss|closest-hit..." as a readable list of Vulkan stage flags.
std::string stageFlagsToString(VkShaderStageFlags flags);
const char* descriptorTypeName(VkDescriptorType t);

struct Define {
  std::string name, value;
  bool operator==(const Define&) const = default;
};
// Why a define cannot be used, or "" when it can: the name must be an identifier, the value one line without
// control characters (a newline would add preprocessor lines of its own), comments, quotes or a final
// backslash (each would run on into the lines after it).
std::string defineProblem(const Define& d);
// A define as a command-line flag gives it ("NAME" or "NAME=VALUE"), checked; throws std::invalid_argument
// starting with `flag` ("--define NAME: ...").
Define parseDefine(const std::string& text, const std::string& flag);

struct ShaderKey {
  fs::path path;
  std::optional<Stage> stage;  // nullopt: from the file extension
  std::vector<Define> defines;
  std::string entry = "main";  // name of the SPIR-V entry point (the GLSL function is always main)
  bool operator==(const ShaderKey&) const = default;
};

struct Diagnostic {
  fs::path file;  // canonical path of the file the message is about (an included file when it is in one)
  int line = 0;   // 1-based; 0 when the message is not about a line
  std::string severity;  // "error" | "warning"
  std::string message;
  // Where it was met: the stages whose compile reported it ("rchit"...; one entry per stage even when an
  // included file's error is met by several), and for an included file the chain of #include lines back to
  // the stage file ("/a.glsl:2 <- /main.rchit:4"). Empty when not known (cached warnings).
  std::vector<std::string> stages;
  std::string includedFrom;
  // file:line: severity: message, then " (in rchit, rmiss; included from ...)" when known.
  std::string toString() const;
  bool operator==(const Diagnostic&) const = default;
};

// Thrown by every failing compile / build / merge. what() is all diagnostics, one per line.
struct CompileError : std::runtime_error {
  explicit CompileError(std::vector<Diagnostic> d);
  std::vector<Diagnostic> diagnostics;
};

struct DescriptorBinding {
  uint32_t set = 0, binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  uint32_t count = 1;         // product of array sizes; 0 for a runtime array
  bool runtimeArray = false;  // unsized array indexed dynamically (descriptor indexing)
  VkShaderStageFlags stages = 0;
  std::string name;
  bool operator==(const DescriptorBinding&) const = default;
};

struct Reflection {
  std::vector<DescriptorBinding> bindings;  // sorted by set, binding; only what the stage uses
  std::vector<VkPushConstantRange> pushConstants;
  // Ray tracing stages: an upper bound of the largest ray payload / callable data and of the hit attributes
  // the stage declares, in bytes (every member counted at 16-byte alignment): what a pipeline library's
  // interface must cover.
  uint32_t rayPayloadBytes = 0;
  uint32_t hitAttributeBytes = 0;
};

struct CompiledShader {
  ShaderKey key;
  Stage stage = Stage::Compute;
  std::vector<uint32_t> spirv;
  std::vector<fs::path> files;       // the file and every file it includes, canonical, main file first
  std::vector<uint64_t> fileHashes;  // xxh3-64 of each file's text as compiled, parallel to files
  bool cacheHit = false;             // true when loaded from the disk cache (no glslang compile)
  double compileMs = 0;              // glslang + validation time (or disk load time on a hit)
  std::vector<Diagnostic> warnings;
  Reflection reflection;
};

struct PipelineLayoutDesc {
  std::vector<DescriptorBinding> bindings;         // sorted set, binding; stage flags unioned
  std::vector<VkPushConstantRange> pushConstants;  // at most one range covering all stages' ranges
};

}  // namespace wb::shader
