#include "shader/compiler.h"

#include "shader/debug_labels.h"
#include "shader/hash.h"
#include "shader/includer.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <spirv-tools/libspirv.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <regex>
#include <sstream>

namespace wb::shader {

namespace {

EShLanguage toLanguage(Stage s) {
  switch (s) {
    case Stage::Vertex:
      return EShLangVertex;
    case Stage::Fragment:
      return EShLangFragment;
    case Stage::Compute:
      return EShLangCompute;
    case Stage::RayGen:
      return EShLangRayGen;
    case Stage::AnyHit:
      return EShLangAnyHit;
    case Stage::ClosestHit:
      return EShLangClosestHit;
    case Stage::Miss:
      return EShLangMiss;
    case Stage::Intersection:
      return EShLangIntersect;
    case Stage::Callable:
      return EShLangCallable;
  }
  return EShLangCompute;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\n' || s.back() == '\r' || s.back() == '\t'))
    s.pop_back();
  size_t i = 0;
  while (i < s.size() && s[i] == ' ') ++i;
  return s.substr(i);
}

// Makes glslang's messages point where the user looks: the stage and, for an included file, the #include
// chain; an include error at its #include line; no follow-on noise ("compilation terminated", errors past the
// end of a file after the real one: glslang's artifacts once it met an error inside an include).
void refineDiagnostics(std::vector<Diagnostic>& diags, const CompileInput& in, const Includer& includer) {
  const bool anyReal = std::any_of(diags.begin(), diags.end(), [](const Diagnostic& d) {
    return d.severity == "error" && d.message.find("compilation terminated") == std::string::npos;
  });
  std::vector<Diagnostic> out;
  bool errorSeen = false;
  for (auto d : diags) {
    if (anyReal && d.message.find("compilation terminated") != std::string::npos) continue;
    // glslang names the preamble "-1": its line N is the Nth define (the scene's specialisation, then
    // --define's). The message names the define instead of "-1:N".
    if (d.file == fs::path("-1") && d.line >= 1 && size_t(d.line) <= in.defines.size()) {
      const Define& def = in.defines[size_t(d.line) - 1];
      d.message = "in the define " + def.name + (def.value.empty() ? "" : "=" + def.value) +
                  " (--define, or the scene's shader specialisation): " + d.message;
      d.file = in.path;
      d.line = 0;
    }
    if (const size_t at = d.message.find("for header name: "); at != std::string::npos) {
      const int line = includer.includeLine(d.file, trim(d.message.substr(at + 17)));
      if (line > 0) d.line = line;
    }
    const size_t lines = includer.lineCount(d.file);
    if (lines > 0 && size_t(d.line) > lines) {
      if (errorSeen && d.severity == "error") continue;  // a follow-on of the error before it
      d.line = int(lines);
    }
    errorSeen = errorSeen || d.severity == "error";
    d.stages = {stageName(in.stage)};
    if (d.file != in.path) d.includedFrom = includer.includeChain(d.file);
    out.push_back(std::move(d));
  }
  diags = std::move(out);
}

}  // namespace

void initCompiler() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

std::string compilerFingerprint() {
  static const std::string fp = [] {
    std::ostringstream os;
    os << "glslang " << GLSLANG_VERSION_MAJOR << '.' << GLSLANG_VERSION_MINOR << '.' << GLSLANG_VERSION_PATCH
       << GLSLANG_VERSION_FLAVOR << "; vulkan1.2; spv1.4; entry point from the key; "
       << spvSoftwareVersionDetailsString();
    return os.str();
  }();
  return fp;
}

std::vector<Diagnostic> parseGlslangLog(const std::string& log, const fs::path& defaultFile) {
  static const std::regex located(R"(^(ERROR|WARNING): (.+?):(\d+): (.*)$)");
  static const std::regex unlocated(R"(^(ERROR|WARNING): (.*)$)");
  std::vector<Diagnostic> out;
  std::istringstream is(log);
  std::string line;
  while (std::getline(is, line)) {
    line = trim(line);
    if (line.empty()) continue;
    std::smatch m;
    if (std::regex_match(line, m, located)) {
      Diagnostic d;
      d.severity = m[1] == "ERROR" ? "error" : "warning";
      std::string file = m[2];
      // glslang names unnamed strings by number ("0:12"); the main file is always named.
      d.file = (file.find_first_not_of("0123456789") == std::string::npos) ? defaultFile : fs::path(file);
      d.line = std::stoi(m[3]);
      d.message = trim(m[4]);
      out.push_back(std::move(d));
    } else if (std::regex_match(line, m, unlocated)) {
      const std::string msg = m[2];
      // Summary lines repeat what was already said.
      if (msg.find("compilation errors.") != std::string::npos ||
          msg.find("compilation warnings.") != std::string::npos)
        continue;
      out.push_back({defaultFile, 0, m[1] == "ERROR" ? "error" : "warning", trim(msg)});
    } else if (!out.empty()) {
      out.back().message += " " + line;  // continuation
    }
  }
  return out;
}

std::optional<std::string> validateSpirv(const std::vector<uint32_t>& spirv, bool scalarBlockLayout) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
  std::string log;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& pos, const char* msg) {
    log += "SPIR-V validation (word " + std::to_string(pos.index) + "): " + msg + "\n";
  });
  spvtools::ValidatorOptions options;
  options.SetScalarBlockLayout(scalarBlockLayout);
  // Friendly names (ids shown by their GLSL names) cost two thirds of the validation and only a failure shows
  // them: a module is checked without them, and a failing one again with them for the message.
  options.SetFriendlyNames(false);
  if (tools.Validate(spirv.data(), spirv.size(), options)) return std::nullopt;
  log.clear();
  options.SetFriendlyNames(true);
  tools.Validate(spirv.data(), spirv.size(), options);
  return log.empty() ? std::string("SPIR-V validation failed") : trim(log);
}

CompileOutput compileGlsl(const CompileInput& in) {
  initCompiler();
  const auto t0 = std::chrono::steady_clock::now();
  const EShLanguage lang = toLanguage(in.stage);
  const std::string mainName = in.path.string();

  std::string preamble;
  for (const auto& d : in.defines)
    preamble += "#define " + d.name + (d.value.empty() ? "" : " " + d.value) + "\n";

  auto shader = std::make_unique<glslang::TShader>(lang);
  // wbPrint / wbAssert labels become ids (shader/debug_labels.h); the includer does the same to every
  // include.
  const std::string source = replaceDebugLabels(in.source);
  const char* strings[] = {source.c_str()};
  const int lengths[] = {static_cast<int>(source.size())};
  const char* names[] = {mainName.c_str()};
  shader->setStringsWithLengthsAndNames(strings, lengths, names, 1);
  shader->setPreamble(preamble.c_str());
  // The GLSL function is main; the SPIR-V entry point takes the key's name (setEntryPoint alone renames
  // nothing).
  shader->setEntryPoint(in.entry.c_str());
  shader->setSourceEntryPoint("main");
  shader->setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
  shader->setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader->setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_4);

  Includer includer(in.path, hash64(in.source), in.includeRoots, &in.sourceOverrides);
  includer.setMainText(in.source);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  const bool parsed = shader->parse(GetDefaultResources(), 460, false, messages, includer);
  std::vector<Diagnostic> diags = parseGlslangLog(shader->getInfoLog(), in.path);
  auto failWith = [&](std::vector<Diagnostic> d, const std::string& fallback) -> CompileError {
    bool anyError = false;
    for (const auto& x : d) anyError |= x.severity == "error";
    if (!anyError) d.push_back({in.path, 0, "error", fallback});
    refineDiagnostics(d, in, includer);
    return CompileError(std::move(d));
  };
  if (!parsed) throw failWith(diags, "compile failed");

  glslang::TProgram program;
  program.addShader(shader.get());
  if (!program.link(messages)) {
    auto linkDiags = parseGlslangLog(program.getInfoLog(), in.path);
    diags.insert(diags.end(), linkDiags.begin(), linkDiags.end());
    throw failWith(diags, "link failed");
  }

  CompileOutput out;
  glslang::SpvOptions spvOptions;
  spvOptions.disableOptimizer = !in.options.optimize;
  spvOptions.optimizeSize = in.options.optimize;
  spvOptions.validate = false;
  spv::SpvBuildLogger logger;
  glslang::GlslangToSpv(*program.getIntermediate(lang), out.spirv, &logger, &spvOptions);
  const std::string spvLog = logger.getAllMessages();
  if (!spvLog.empty()) {
    for (auto& d : parseGlslangLog(spvLog, in.path)) diags.push_back(std::move(d));
  }

  if (in.options.validate) {
    const bool scalarBlockLayout = in.source.find("GL_EXT_scalar_block_layout") != std::string::npos ||
                                   includer.mentions("GL_EXT_scalar_block_layout");
    if (auto problem = validateSpirv(out.spirv, scalarBlockLayout)) {
      diags.push_back({in.path, 0, "error", *problem});
      refineDiagnostics(diags, in, includer);
      throw CompileError(std::move(diags));
    }
  }

  for (auto& d : diags)
    if (d.severity == "warning") out.warnings.push_back(std::move(d));
  for (const auto& f : includer.files()) {
    out.files.push_back(f.path);
    out.contentHashes.push_back(f.contentHash);
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace wb::shader
