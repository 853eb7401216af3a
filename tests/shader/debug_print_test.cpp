// wbPrint / wbAssert (shaders/shared/debug_print.h): the labels' string literals become ids before glslang
// (shader/debug_labels.h), and the calls compile to nothing unless a debug variant is on, so the default
// SPIR-V of every path tracer stage is byte-identical with and without them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "common/paths.h"
#include "shader/debug_labels.h"
#include "shader/library.h"
#include "test_util.h"

using namespace wb::shader;
using namespace wb::shader::test;

TEST(DebugLabels, StringLiteralsBecomeIdsOutsideCommentsAndDirectives) {
  const std::string src =
      "#include \"a.glsl\"\n"
      "// wbPrint(\"in a comment\", x);\n"
      "/* \"block\"\n \"comment\" */\n"
      "#define M(x) wbPrint(\"in a macro\", x)\n"
      "void f() { wbPrint(\"pdf\", p); wbAssert(p > 0.0, \"a \\\"quoted\\\" word\"); }\n"
      "void g() { debugPrintfEXT( \"x %f\", p); }\n";
  std::map<uint32_t, std::string> labels;
  const std::string out = replaceDebugLabels(src, &labels);
  char pdf[16], quoted[16];
  std::snprintf(pdf, sizeof pdf, "0x%08xu", debugLabelId("pdf"));
  std::snprintf(quoted, sizeof quoted, "0x%08xu", debugLabelId("a \"quoted\" word"));
  EXPECT_NE(out.find(std::string("wbPrint(") + pdf + ", p)"), std::string::npos) << out;
  EXPECT_NE(out.find(std::string("\"a.glsl\"")), std::string::npos) << "an #include keeps its quotes";
  EXPECT_NE(out.find("\"in a comment\""), std::string::npos);
  EXPECT_NE(out.find("\"block\"\n \"comment\""), std::string::npos);
  EXPECT_NE(out.find("\"in a macro\""), std::string::npos) << "a preprocessor line keeps its strings";
  EXPECT_NE(out.find(quoted), std::string::npos) << out;
  EXPECT_NE(out.find("debugPrintfEXT( \"x %f\", p)"), std::string::npos) << "its format stays a string";
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(src.begin(), src.end(), '\n'))
      << "lines are kept (diagnostics name the source's lines)";
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[debugLabelId("pdf")], "pdf");
  EXPECT_EQ(labels[debugLabelId("a \"quoted\" word")], "a \"quoted\" word");
  EXPECT_EQ(debugLabelId(""), 2166136261u);  // FNV-1a's offset basis
}

namespace {

// The SPIR-V of shaders/pathtracer/<stage> (the copy under `root`) with `defines`, from a fresh library.
std::vector<uint32_t> spirvOf(const fs::path& root, const std::string& stage,
                              const std::vector<Define>& defines) {
  ShaderLibrary lib({.includeRoots = {root}, .cacheDir = {}, .printWarnings = false});
  return lib.compile({root / "pathtracer" / stage, std::nullopt, defines})->spirv;
}

}  // namespace

TEST(DebugPrint, UnusedCallsLeaveTheDefaultSpirvUnchanged) {
  TempDir t;
  const fs::path root = t / "shaders";
  fs::copy(wb::shaderDir(), root, fs::copy_options::recursive);
  const std::string calls =
      "  wbPrint(\"one float\", 1.5);\n  wbPrint(\"a vector\", vec3(gl_LaunchIDEXT));\n"
      "  wbPrint(\"a uint\", gl_LaunchIDEXT.x);\n  wbPrint(\"a bool\", gl_LaunchIDEXT.y > 3u);\n"
      "  wbAssert(gl_LaunchIDEXT.x < 100000u, \"in range\");\n";
  for (const std::string stage :
       {"raygen.rgen", "closesthit.rchit", "miss.rmiss", "shadow.rmiss", "anyhit.rahit"}) {
    SCOPED_TRACE(stage);
    const fs::path file = root / "pathtracer" / stage;
    const std::string original = readAll(file);
    const std::vector<std::vector<Define>> variants = {{}, {{"WB_CPU_DEVICE", "1"}}};
    std::vector<std::vector<uint32_t>> before;
    for (const auto& v : variants) before.push_back(spirvOf(root, stage, v));
    const auto inspectBefore = spirvOf(root, stage, {{"WB_INSPECT", "1"}});
    const auto assertsBefore = spirvOf(root, stage, {{"WB_ASSERTS", "1"}});

    // The calls at the start of main, and the header included once more by the user.
    std::string edited = original;
    const size_t at = edited.find("void main() {\n");
    ASSERT_NE(at, std::string::npos);
    edited.insert(at + 14, calls);
    edited.insert(edited.find('\n') + 1, "#extension GL_GOOGLE_include_directive : require\n");
    edited.insert(edited.find("void main() {\n"), "#include \"../shared/debug_print.h\"\n");
    writeFile(file, edited);
    for (size_t i = 0; i < variants.size(); ++i)
      EXPECT_EQ(spirvOf(root, stage, variants[i]), before[i]) << "variant " << i;
    // The debug variants compile the calls: the comparison can fail.
    EXPECT_NE(spirvOf(root, stage, {{"WB_INSPECT", "1"}}), inspectBefore);
    EXPECT_NE(spirvOf(root, stage, {{"WB_ASSERTS", "1"}}), assertsBefore);
    writeFile(file, original);
  }
}
