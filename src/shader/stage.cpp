#include "shader/types.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

namespace wb::shader {

namespace {
struct StageInfo {
  Stage stage;
  const char* ext;
  VkShaderStageFlagBits vk;
};
constexpr StageInfo kStages[] = {
    {Stage::Vertex, "vert", VK_SHADER_STAGE_VERTEX_BIT},
    {Stage::Fragment, "frag", VK_SHADER_STAGE_FRAGMENT_BIT},
    {Stage::Compute, "comp", VK_SHADER_STAGE_COMPUTE_BIT},
    {Stage::RayGen, "rgen", VK_SHADER_STAGE_RAYGEN_BIT_KHR},
    {Stage::AnyHit, "rahit", VK_SHADER_STAGE_ANY_HIT_BIT_KHR},
    {Stage::ClosestHit, "rchit", VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR},
    {Stage::Miss, "rmiss", VK_SHADER_STAGE_MISS_BIT_KHR},
    {Stage::Intersection, "rint", VK_SHADER_STAGE_INTERSECTION_BIT_KHR},
    {Stage::Callable, "rcall", VK_SHADER_STAGE_CALLABLE_BIT_KHR},
};

std::optional<Stage> fromExt(std::string ext) {
  if (!ext.empty() && ext[0] == '.') ext = ext.substr(1);
  for (const auto& s : kStages)
    if (ext == s.ext) return s.stage;
  return std::nullopt;
}
}  // namespace

VkShaderStageFlagBits toVkStage(Stage s) {
  return kStages[static_cast<int>(s)].vk;
}
const char* stageName(Stage s) {
  return kStages[static_cast<int>(s)].ext;
}

std::optional<Stage> stageFromPath(const fs::path& p) {
  if (auto s = fromExt(p.extension().string())) return s;
  if (p.extension() == ".glsl") return fromExt(p.stem().extension().string());
  return std::nullopt;
}

std::string stageFlagsToString(VkShaderStageFlags flags) {
  std::string out;
  for (const auto& s : kStages) {
    if (flags & s.vk) {
      if (!out.empty()) out += '|';
      out += s.ext;
    }
  }
  return out.empty() ? "none" : out;
}

const char* descriptorTypeName(VkDescriptorType t) {
  switch (t) {
    case VK_DESCRIPTOR_TYPE_SAMPLER:
      return "sampler";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
      return "combined-image-sampler";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
      return "sampled-image";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
      return "storage-image";
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
      return "uniform-texel-buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
      return "storage-texel-buffer";
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
      return "uniform-buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
      return "storage-buffer";
    case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
      return "input-attachment";
    case VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR:
      return "acceleration-structure";
    default:
      return "unknown";
  }
}

std::string Diagnostic::toString() const {
  std::ostringstream os;
  os << file.string() << ':' << line << ": " << severity << ": " << message;
  if (!stages.empty() || !includedFrom.empty()) {
    os << " (";
    for (size_t i = 0; i < stages.size(); ++i) os << (i ? ", " : "in ") << stages[i];
    if (!includedFrom.empty()) os << (stages.empty() ? "" : "; ") << "included from " << includedFrom;
    os << ')';
  }
  return os.str();
}

namespace {
std::string joinDiagnostics(const std::vector<Diagnostic>& d) {
  std::string out;
  for (const auto& x : d) {
    if (!out.empty()) out += '\n';
    out += x.toString();
  }
  return out.empty() ? "shader compile error" : out;
}
}  // namespace

CompileError::CompileError(std::vector<Diagnostic> d)
    : std::runtime_error(joinDiagnostics(d)), diagnostics(std::move(d)) {}

std::string defineProblem(const Define& d) {
  const bool identifier =
      !d.name.empty() && !std::isdigit(static_cast<unsigned char>(d.name[0])) &&
      std::all_of(d.name.begin(), d.name.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
  if (!identifier)
    return "'" + d.name + "' is not an identifier (letters, digits, _; not starting with a digit)";
  if (std::any_of(d.value.begin(), d.value.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
    return "the value of " + d.name + " holds a newline or another control character";
  // The value goes into a `#define` line of the shaders' preamble: a comment or a string it opens would run
  // on into the shader's own first lines, and a backslash at its end would join the next line to it.
  if (d.value.find("/*") != std::string::npos || d.value.find("//") != std::string::npos)
    return "the value of " + d.name + " opens a comment (/* or //)";
  if (d.value.find('"') != std::string::npos) return "the value of " + d.name + " holds a quote (\")";
  if (!d.value.empty() && d.value.back() == '\\')
    return "the value of " + d.name + " ends in a backslash (it would continue the line)";
  return "";
}

Define parseDefine(const std::string& text, const std::string& flag) {
  const auto eq = text.find('=');
  Define d{text.substr(0, eq), eq == std::string::npos ? std::string() : text.substr(eq + 1)};
  const std::string problem = defineProblem(d);
  if (!problem.empty()) {
    std::string shown;  // control characters made visible: the message stays one line
    for (unsigned char c : text)
      shown += c == '\n' ? std::string("\\n") : c < 0x20 ? std::string("?") : std::string(1, char(c));
    throw std::invalid_argument(flag + " '" + shown + "': expected NAME or NAME=VALUE; " + problem);
  }
  return d;
}

}  // namespace wb::shader
