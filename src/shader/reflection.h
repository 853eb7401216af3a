// Descriptor / push-constant reflection of one SPIR-V stage (SPIRV-Cross, active resources only) and the
// merge of several stages into one pipeline layout description.
#pragma once
#include "shader/types.h"

#include <memory>

namespace wb::shader {

// Throws CompileError (attached to `file`) when SPIRV-Cross cannot parse the module.
Reflection reflectSpirv(const std::vector<uint32_t>& spirv, Stage stage, const fs::path& file);

// Union of stage flags per (set, binding); a runtime array wins over a sized declaration of the same binding
// (glslang sizes an unsized array that a stage never indexes to 1). Different descriptor types or counts at
// the same set/binding throw CompileError with one diagnostic per file (both files named).
PipelineLayoutDesc mergeLayouts(const std::vector<std::shared_ptr<const CompiledShader>>& stages);

}  // namespace wb::shader
