// Descriptor / push-constant reflection of one SPIR-V stage (SPIRV-Cross, active resources only) and the
// merge of several stages into one pipeline layout description.
#pragma once
#include "shader/types.h"

#include <memory>
#include <utility>

namespace wb::shader {

// Throws CompileError (attached to `file`) when SPIRV-Cross cannot parse the module.
Reflection reflectSpirv(const std::vector<uint32_t>& spirv, Stage stage, const fs::path& file);

// Where a reflected resource is declared: the first line of the stage's files (main file first, then its
// includes) that names it (block or variable name) on or just below a layout(...) qualifier, else the first
// line with its literal "binding = N"; else the main file, line 0. Read from the files as they are now.
std::pair<fs::path, int> findDeclaration(const CompiledShader& stage, const DescriptorBinding& binding);

// Throws CompileError when one stage declares resources of different descriptor types at one set/binding
// (used or not), at the file:line of each declaration.
void checkBindingAliases(const CompiledShader& stage);

// Union of stage flags per (set, binding); a runtime array wins over a sized declaration of the same binding
// (glslang sizes an unsized array that a stage never indexes to 1). Different descriptor types or counts at
// the same set/binding throw CompileError with one diagnostic per file (both files named).
PipelineLayoutDesc mergeLayouts(const std::vector<std::shared_ptr<const CompiledShader>>& stages);

}  // namespace wb::shader
