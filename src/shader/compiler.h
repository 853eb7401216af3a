// One GLSL -> SPIR-V compile with the glslang C++ API (Vulkan 1.2, SPIR-V 1.4), optional spirv-opt, and
// SPIR-V validation with SPIRV-Tools. No caching here (see ShaderLibrary).
#pragma once
#include "shader/types.h"

#include <cstdint>
#include <optional>
#include <map>
#include <string>
#include <vector>

namespace wb::shader {

struct CompileOptions {
  bool optimize = false;
  bool validate = true;
};

struct CompileInput {
  fs::path path;  // canonical
  std::string source;
  Stage stage;
  std::vector<Define> defines;
  std::string entry = "main";
  std::vector<fs::path> includeRoots;
  CompileOptions options;
  // Texts read instead of these (canonical) include files: sources a revert keeps (ShaderLibrary).
  std::map<fs::path, std::string> sourceOverrides;
};

struct CompileOutput {
  std::vector<uint32_t> spirv;
  std::vector<fs::path> files;          // main file first, then includes
  std::vector<uint64_t> contentHashes;  // xxh3-64 of exactly what was compiled, parallel to files
  std::vector<Diagnostic> warnings;
  double ms = 0;
};

// glslang::InitializeProcess once per process (thread-safe); called by compileGlsl.
void initCompiler();
// Throws CompileError with file:line diagnostics (also inside included files).
CompileOutput compileGlsl(const CompileInput& in);
// SPIR-V validation for Vulkan 1.2 (the validation compileGlsl runs): nothing when valid, else the
// validator's messages with ids shown by their names.
std::optional<std::string> validateSpirv(const std::vector<uint32_t>& spirv, bool scalarBlockLayout);
// A string that changes when the compiler or its settings change (glslang version, target env, SPIR-V
// version).
std::string compilerFingerprint();
// Parses glslang's info log ("ERROR: file:line: message") into diagnostics; lines without a location are
// attached to defaultFile, line 0.
std::vector<Diagnostic> parseGlslangLog(const std::string& log, const fs::path& defaultFile);

}  // namespace wb::shader
