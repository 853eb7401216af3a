// The labels of wbPrint("label", value) and wbAssert(condition, "label") (shaders/shared/debug_print.h).
// GLSL has no strings: before glslang sees a shader, every string literal of its code (outside comments,
// preprocessor lines, whose #include "file" keeps its quotes, and debugPrintfEXT's format) becomes the
// label's id, a uint literal with the 32-bit FNV-1a hash of its text. The id is the same in every stage and
// file, so the host maps the ids a shader recorded back to texts by reading the same sources again
// (debugLabelsOf). Lines are kept: a diagnostic's line is the source's.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace wb::shader {

// FNV-1a of the label's text (what a literal "text" becomes: 0x%08xu).
uint32_t debugLabelId(std::string_view text);

// `source` with its string literals replaced by their ids; `labels` (optional) gets id -> text. A literal
// that does not end on its line is left as it is (glslang then reports it). A backslash escapes the next
// character of a label ("a \"quoted\" word").
std::string replaceDebugLabels(std::string_view source, std::map<uint32_t, std::string>* labels = nullptr);

// The labels of `files` (a compiled shader's main file and includes), read now. Two texts with one id (a hash
// collision) are kept as "text1 | text2".
std::map<uint32_t, std::string> debugLabelsOf(const std::vector<std::filesystem::path>& files);

}  // namespace wb::shader
