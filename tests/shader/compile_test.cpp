// Compiler, includes, stage detection, diagnostics and reflection.
#include "shader/compiler.h"
#include "shader/hit_object.h"
#include "shader/library.h"
#include "test_util.h"

#include <algorithm>
#include <atomic>
#include <thread>

using namespace wb::shader;
using namespace wb::shader::test;

TEST(ShaderStage, FromPath) {
  EXPECT_EQ(stageFromPath("a/b.rgen"), Stage::RayGen);
  EXPECT_EQ(stageFromPath("x.rmiss"), Stage::Miss);
  EXPECT_EQ(stageFromPath("x.rchit"), Stage::ClosestHit);
  EXPECT_EQ(stageFromPath("x.rahit"), Stage::AnyHit);
  EXPECT_EQ(stageFromPath("x.rint"), Stage::Intersection);
  EXPECT_EQ(stageFromPath("x.rcall"), Stage::Callable);
  EXPECT_EQ(stageFromPath("x.vert"), Stage::Vertex);
  EXPECT_EQ(stageFromPath("x.frag"), Stage::Fragment);
  EXPECT_EQ(stageFromPath("x.comp"), Stage::Compute);
  EXPECT_EQ(stageFromPath("shade.rchit.glsl"), Stage::ClosestHit);
  EXPECT_EQ(stageFromPath("common.glsl"), std::nullopt);
  EXPECT_EQ(stageFromPath("x.h"), std::nullopt);
  EXPECT_EQ(toVkStage(Stage::RayGen), VK_SHADER_STAGE_RAYGEN_BIT_KHR);
  EXPECT_EQ(toVkStage(Stage::Fragment), VK_SHADER_STAGE_FRAGMENT_BIT);
}

TEST(ShaderCompile, IncludeAndDefines) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "#define VALUE (BASE + 1u)\n");
  ShaderLibrary lib({});
  auto s = lib.compile({t / "a.comp", std::nullopt, {{"BASE", "41u"}}});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->stage, Stage::Compute);
  EXPECT_FALSE(s->spirv.empty());
  EXPECT_EQ(s->spirv[0], 0x07230203u);
  ASSERT_EQ(s->files.size(), 2u);
  EXPECT_EQ(s->files[0], t / "a.comp");
  EXPECT_EQ(s->files[1], t / "inc.glsl");
  ASSERT_EQ(s->reflection.bindings.size(), 1u);
  EXPECT_EQ(s->reflection.bindings[0].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  // Without the define it does not compile.
  EXPECT_THROW(lib.compile({t / "a.comp"}), CompileError);
}

TEST(ShaderCompile, IncludeRootsAndStageOverride) {
  TempDir t;
  writeFile(t / "src/main.glsl", kComputeMain);
  writeFile(t / "lib/inc.glsl", "#define VALUE 7u\n");
  ShaderLibrary lib({.includeRoots = {t / "lib"}});
  auto s = lib.compile({t / "src/main.glsl", Stage::Compute});
  EXPECT_EQ(s->files.back(), t / "lib/inc.glsl");
  // No stage from the name and none given: a clear error.
  try {
    lib.compile({t / "src/main.glsl"});
    FAIL();
  } catch (const CompileError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown shader stage"), std::string::npos) << e.what();
  }
}

TEST(ShaderCompile, ErrorInIncludedFileHasFileAndLine) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "// line 1\n// line 2\nconst uint x = undefinedThing;\n#define VALUE 1u\n");
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.comp"});
    FAIL() << "expected an error";
  } catch (const CompileError& e) {
    ASSERT_FALSE(e.diagnostics.empty()) << e.what();
    const auto& d = e.diagnostics.front();
    EXPECT_EQ(d.file, t / "inc.glsl") << e.what();
    EXPECT_EQ(d.line, 3) << e.what();
    EXPECT_EQ(d.severity, "error");
    EXPECT_NE(d.toString().find((t / "inc.glsl").string() + ":3: error: "), std::string::npos)
        << d.toString();
  }
  auto st = lib.fileStatuses();
  ASSERT_TRUE(st.count(t / "inc.glsl"));
  EXPECT_FALSE(st[t / "inc.glsl"].ok);
  EXPECT_FALSE(st[t / "a.comp"].ok);
}

TEST(ShaderCompile, ErrorInMainFileLineIsRight) {
  TempDir t;
  writeFile(t / "a.comp", std::string(kComputeMain) + "void f() { int y = nope; }\n");
  writeFile(t / "inc.glsl", "#define VALUE 1u\n");
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.comp", std::nullopt, {{"UNUSED", "1"}}});
    FAIL();
  } catch (const CompileError& e) {
    ASSERT_FALSE(e.diagnostics.empty());
    EXPECT_EQ(e.diagnostics.front().file, t / "a.comp") << e.what();
    EXPECT_EQ(e.diagnostics.front().line, 7) << e.what();
  }
}

TEST(ShaderCompile, WarningsAreKept) {
  TempDir t;
  writeFile(t / "a.comp", std::string(kComputeMain) + "#extension GL_EXT_nonexistent_thing : warn\n");
  writeFile(t / "inc.glsl", "#define VALUE 1u\n");
  ShaderLibrary lib({});
  auto s = lib.compile({t / "a.comp"});
  ASSERT_FALSE(s->warnings.empty());
  EXPECT_EQ(s->warnings[0].severity, "warning");
  EXPECT_EQ(s->warnings[0].file, t / "a.comp");
  EXPECT_EQ(s->warnings[0].line, 7);
}

// The names of the SPIR-V module's OpEntryPoint instructions.
std::vector<std::string> entryPointNames(const std::vector<uint32_t>& spirv) {
  std::vector<std::string> names;
  for (size_t i = 5; i < spirv.size();) {
    const uint32_t words = spirv[i] >> 16, opcode = spirv[i] & 0xFFFFu;
    if (words == 0) break;
    if (opcode == 15 && i + 3 < spirv.size())  // OpEntryPoint: model, id, then the name
      names.emplace_back(reinterpret_cast<const char*>(&spirv[i + 3]));
    i += words;
  }
  return names;
}

TEST(ShaderCompile, EntryPointIsNamedByTheKey) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "#define VALUE 1u\n");
  ShaderLibrary lib({});
  ShaderKey k{t / "a.comp"};
  EXPECT_EQ(entryPointNames(lib.compile(k)->spirv), std::vector<std::string>{"main"});
  k.entry = "fill";  // a variant of its own, its GLSL main exported under that name
  const auto renamed = lib.compile(k);
  EXPECT_EQ(entryPointNames(renamed->spirv), std::vector<std::string>{"fill"});
  EXPECT_EQ(renamed->key.entry, "fill");
}

TEST(ShaderCompile, IncludeCycleIsAClearError) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "#include \"other.glsl\"\n#define VALUE 1u\n");
  writeFile(t / "other.glsl", "\n#include \"inc.glsl\"\n");
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.comp"});
    FAIL();
  } catch (const CompileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("include cycle"), std::string::npos) << what;
    EXPECT_NE(what.find("inc.glsl"), std::string::npos) << what;
    EXPECT_EQ(e.diagnostics.front().file, t / "other.glsl") << what;
    EXPECT_EQ(e.diagnostics.front().line, 2) << what;
  }
}

TEST(ShaderCompile, MissingIncludeIsAClearError) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.comp"});
    FAIL();
  } catch (const CompileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("include file not found: \"inc.glsl\""), std::string::npos) << what;
    EXPECT_EQ(e.diagnostics.front().file, t / "a.comp") << what;
    EXPECT_EQ(e.diagnostics.front().line, 3) << what;
  }
}

TEST(ShaderCompile, MissingFile) {
  TempDir t;
  ShaderLibrary lib({});
  try {
    lib.compile({t / "nope.rgen"});
    FAIL();
  } catch (const CompileError& e) {
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

namespace {
const DescriptorBinding* find(const PipelineLayoutDesc& l, uint32_t binding) {
  for (const auto& b : l.bindings)
    if (b.set == 0 && b.binding == binding) return &b;
  return nullptr;
}
}  // namespace

TEST(ShaderReflect, RayTracingProgramLayout) {
  ShaderLibrary lib({});
  const fs::path d = dataDir() / "rt";
  auto id =
      lib.registerProgram("rt", {{d / "rt.rgen"}, {d / "rt.rmiss"}, {d / "rt.rchit"}, {d / "rt.rahit"}});
  auto build = lib.buildProgram(id);
  ASSERT_EQ(build.stages.size(), 4u);
  const auto& l = build.layout;
  ASSERT_EQ(l.bindings.size(), 6u);
  const auto rgen = VK_SHADER_STAGE_RAYGEN_BIT_KHR, miss = VK_SHADER_STAGE_MISS_BIT_KHR,
             chit = VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, ahit = VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
  struct Expect {
    uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
    bool runtime;
  } expected[] = {
      {0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, rgen, false},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, rgen, false},
      {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VkShaderStageFlags(rgen | miss), false},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VkShaderStageFlags(chit | ahit), false},
      {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VkShaderStageFlags(rgen | chit), false},
      {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VkShaderStageFlags(chit | ahit), true},
  };
  for (const auto& e : expected) {
    const auto* b = find(l, e.binding);
    ASSERT_TRUE(b) << "binding " << e.binding;
    EXPECT_EQ(b->type, e.type) << "binding " << e.binding;
    EXPECT_EQ(b->stages, e.stages) << "binding " << e.binding << ": " << stageFlagsToString(b->stages);
    EXPECT_EQ(b->runtimeArray, e.runtime) << "binding " << e.binding;
    if (!e.runtime) {
      EXPECT_EQ(b->count, 1u);
    }
  }
  EXPECT_EQ(find(l, 5)->name, "textures");
  // The any-hit alone sees textures[] as a 1-element array (constant index).
  const auto& ahitRefl = build.stages[3]->reflection;
  auto it = std::find_if(ahitRefl.bindings.begin(), ahitRefl.bindings.end(),
                         [](const DescriptorBinding& b) { return b.binding == 5; });
  ASSERT_NE(it, ahitRefl.bindings.end());
  EXPECT_FALSE(it->runtimeArray);
  EXPECT_EQ(it->count, 1u);
  ASSERT_EQ(l.pushConstants.size(), 1u);
  EXPECT_EQ(l.pushConstants[0].offset, 0u);
  EXPECT_EQ(l.pushConstants[0].size, 8u);
  EXPECT_EQ(l.pushConstants[0].stageFlags, VkShaderStageFlags(rgen | chit));
}

// Debian's SPIRV-Cross cannot parse shader execution reordering's hit object; the reflection reads the module
// with each hit object trace as the plain trace it stands for, so the layout is the one the plain trace gives.
TEST(ShaderReflect, AHitObjectTraceIsReflectedAsThePlainTrace) {
  ShaderLibrary lib({});
  const fs::path d = dataDir() / "rt";
  const std::vector<ShaderKey> plainKeys = {{d / "rt.rgen"}, {d / "rt.rmiss"}, {d / "rt.rchit"}};
  std::vector<ShaderKey> reorderKeys = plainKeys;
  reorderKeys[0].defines.push_back({"REORDER", "1"});
  const auto plain = lib.buildProgram(lib.registerProgram("plain", plainKeys));
  const auto reorder = lib.buildProgram(lib.registerProgram("reorder", reorderKeys));
  const auto& spirv = reorder.stages[0]->spirv;
  ASSERT_TRUE(usesHitObjects(spirv));
  EXPECT_FALSE(usesHitObjects(plain.stages[0]->spirv));
  auto count = [](const std::vector<uint32_t>& m, uint32_t opcode) {
    int n = 0;
    for (size_t i = 5; i < m.size() && (m[i] >> 16) != 0; i += m[i] >> 16) n += (m[i] & 0xFFFFu) == opcode;
    return n;
  };
  constexpr uint32_t kOpTraceRayKHR = 4445, kOpHitObjectTraceRayNV = 5260, kOpTypeHitObjectNV = 5281;
  EXPECT_EQ(count(spirv, kOpTraceRayKHR), 0);
  EXPECT_EQ(count(spirv, kOpHitObjectTraceRayNV), 1);
  const auto seen = withoutHitObjects(spirv);
  EXPECT_EQ(count(seen, kOpTraceRayKHR), 1);
  EXPECT_EQ(count(seen, kOpHitObjectTraceRayNV) + count(seen, kOpTypeHitObjectNV), 0);
  // The same layout and payload: the acceleration structure and the payload stay in use through the trace.
  const auto& a = plain.stages[0]->reflection;
  const auto& b = reorder.stages[0]->reflection;
  ASSERT_EQ(a.bindings.size(), b.bindings.size());
  for (size_t i = 0; i < a.bindings.size(); ++i) {
    EXPECT_EQ(a.bindings[i].binding, b.bindings[i].binding);
    EXPECT_EQ(a.bindings[i].type, b.bindings[i].type);
    EXPECT_EQ(a.bindings[i].name, b.bindings[i].name);
  }
  ASSERT_TRUE(find(reorder.layout, 0));
  EXPECT_EQ(find(reorder.layout, 0)->type, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR);
  EXPECT_GT(b.rayPayloadBytes, 0u);
  EXPECT_EQ(a.rayPayloadBytes, b.rayPayloadBytes);
  ASSERT_EQ(b.pushConstants.size(), a.pushConstants.size());
  EXPECT_EQ(withoutHitObjects(plain.stages[0]->spirv), plain.stages[0]->spirv);
}

TEST(ShaderReflect, BindingConflictNamesBothFiles) {
  TempDir t;
  writeFile(t / "a.rgen", R"(#version 460
#extension GL_EXT_ray_tracing : require
layout(set = 0, binding = 2) uniform U { vec4 c; } u;
layout(set = 0, binding = 1, rgba8) uniform image2D img;
void main() { imageStore(img, ivec2(0), u.c); }
)");
  writeFile(t / "b.rmiss", R"(#version 460
#extension GL_EXT_ray_tracing : require
layout(location = 0) rayPayloadInEXT vec4 p;
layout(set = 0, binding = 2, std430) buffer S { vec4 c; } s;
void main() { p = s.c; }
)");
  ShaderLibrary lib({});
  auto id = lib.registerProgram("conflict", {{t / "a.rgen"}, {t / "b.rmiss"}});
  try {
    lib.buildProgram(id);
    FAIL();
  } catch (const CompileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find((t / "a.rgen").string()), std::string::npos) << what;
    EXPECT_NE(what.find((t / "b.rmiss").string()), std::string::npos) << what;
    EXPECT_NE(what.find("set 0 binding 2"), std::string::npos) << what;
    EXPECT_NE(what.find("uniform-buffer"), std::string::npos) << what;
    EXPECT_NE(what.find("storage-buffer"), std::string::npos) << what;
    // At the declarations' lines, not line 0.
    ASSERT_EQ(e.diagnostics.size(), 2u) << what;
    EXPECT_EQ(e.diagnostics[0].file, t / "a.rgen");
    EXPECT_EQ(e.diagnostics[0].line, 3) << what;
    EXPECT_EQ(e.diagnostics[1].file, t / "b.rmiss");
    EXPECT_EQ(e.diagnostics[1].line, 4) << what;
  }
}

// Two descriptor types at one set/binding inside one stage: glslang accepts it, a pipeline layout cannot.
TEST(ShaderReflect, TwoTypesAtOneBindingInOneFileIsAnError) {
  TempDir t;
  writeFile(t / "a.rmiss", R"(#version 460
#extension GL_EXT_ray_tracing : require
layout(location = 0) rayPayloadInEXT vec3 p;
layout(set = 0, binding = 3) uniform U { vec4 a; } u;
layout(set = 0, binding = 3, std430) buffer B { vec4 b[]; } bb;
void main() { p = u.a.xyz + bb.b[0].xyz; }
)");
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.rmiss"});
    FAIL() << "reported ok";
  } catch (const CompileError& e) {
    ASSERT_EQ(e.diagnostics.size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics[0].line, 5) << e.what();
    EXPECT_NE(e.diagnostics[0].message.find("binding conflict at set 0 binding 3"), std::string::npos);
    EXPECT_NE(e.diagnostics[0].message.find("a.rmiss:4"), std::string::npos) << e.what();
  }
}

// An error in a nested include: said once for the program, with every stage that met it and the #include
// chain; no follow-on errors after it.
TEST(ShaderCompile, NestedIncludeErrorOnceWithStagesAndChain) {
  TempDir t;
  writeFile(t / "b.glsl", "// b\nfloat broken() { return undefinedThing; }\n");
  writeFile(t / "a.glsl", "// a\n#include \"b.glsl\"");  // no newline at the end
  const std::string head =
      "#version 460\n#extension GL_EXT_ray_tracing : require\n"
      "#extension GL_GOOGLE_include_directive : require\n#include \"a.glsl\"\n";
  writeFile(t / "m.rmiss",
            head + "layout(location = 0) rayPayloadInEXT vec3 p;\nvoid main() { p = vec3(broken()); }\n");
  writeFile(t / "g.rgen", head + "void main() { float x = broken(); }\n");
  ShaderLibrary lib({});
  auto id = lib.registerProgram("p", {{t / "g.rgen"}, {t / "m.rmiss"}});
  try {
    lib.buildProgram(id);
    FAIL();
  } catch (const CompileError& e) {
    ASSERT_EQ(e.diagnostics.size(), 1u) << e.what();
    const auto& d = e.diagnostics[0];
    EXPECT_EQ(d.file, t / "b.glsl");
    EXPECT_EQ(d.line, 2);
    EXPECT_EQ(d.stages, (std::vector<std::string>{"rgen", "rmiss"})) << e.what();
    EXPECT_EQ(d.includedFrom, (t / "a.glsl").string() + ":2 <- " + (t / "g.rgen").string() + ":4")
        << e.what();
    EXPECT_NE(d.toString().find("(in rgen, rmiss; included from "), std::string::npos) << d.toString();
  }
}

// The include-cycle error is at the #include line, inside the file, also when it is the last line without a
// newline.
TEST(ShaderCompile, IncludeCycleLineIsInsideTheFile) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "#define VALUE 1u\n#include \"other.glsl\"\n");
  writeFile(t / "other.glsl", "// other\n#include \"inc.glsl\"");
  ShaderLibrary lib({});
  try {
    lib.compile({t / "a.comp"});
    FAIL();
  } catch (const CompileError& e) {
    ASSERT_FALSE(e.diagnostics.empty());
    EXPECT_EQ(e.diagnostics.front().file, t / "other.glsl") << e.what();
    EXPECT_EQ(e.diagnostics.front().line, 2) << e.what();
  }
}

// After a failed compile is fixed, the files only the failed version touched are no longer dependencies.
TEST(ShaderCompile, FixedCompileForgetsTheFilesOfTheFailure) {
  TempDir t;
  writeFile(t / "a.comp", kComputeMain);
  writeFile(t / "inc.glsl", "#define VALUE 1u\n");
  writeFile(t / "broken.glsl", "const uint z = nope;\n#define VALUE 1u\n");
  ShaderLibrary lib({});
  const auto id = lib.registerProgram("p", {{t / "a.comp"}});
  lib.buildProgram(id);
  EXPECT_TRUE(lib.programsDependingOn(t / "broken.glsl").empty());
  const std::string good = readAll(t / "a.comp");
  std::string bad = good;
  bad.replace(bad.find("inc.glsl"), 8, "broken.glsl");
  writeFile(t / "a.comp", bad);
  lib.invalidateFiles({t / "a.comp"});
  EXPECT_THROW(lib.buildProgram(id), CompileError);
  EXPECT_EQ(lib.programsDependingOn(t / "broken.glsl").size(), 1u);
  writeFile(t / "a.comp", good);  // the fix: back to the compiled version (a memory hit)
  lib.invalidateFiles({t / "a.comp"});
  lib.buildProgram(id);
  EXPECT_TRUE(lib.programsDependingOn(t / "broken.glsl").empty()) << "editing it would rebuild the program";
  EXPECT_EQ(lib.programsDependingOn(t / "inc.glsl").size(), 1u);
}

TEST(ShaderCompile, ThreadSafe) {
  TempDir t;
  writeFile(t / "inc.glsl", "#define VALUE BASE\n");
  writeFile(t / "a.comp", kComputeMain);
  ShaderLibrary lib({.cacheDir = t / "cache", .printWarnings = false});
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int i = 0; i < 4; ++i)
    threads.emplace_back([&, i] {
      for (int j = 0; j < 8; ++j) {
        try {
          lib.compile({t / "a.comp", std::nullopt, {{"BASE", std::to_string((i + j) % 5) + "u"}}});
        } catch (...) {
          ++failures;
        }
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(lib.stats().hits + lib.stats().misses, 32u);
  EXPECT_TRUE(lib.cacheWarnings().empty());
}

// A module that glslang wrote but the validator refuses: the error is reported, and its message names the
// ids by their GLSL names (the validator runs without names first, and again with them only on failure).
TEST(ShaderCompile, InvalidSpirvIsRefusedWithNamedIds) {
  TempDir t;
  writeFile(t / "a.comp", R"(#version 460
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) buffer Out { uint counterValue; } outBuf;
void main() { outBuf.counterValue = 3u; }
)");
  CompileInput in{t / "a.comp", readAll(t / "a.comp"), Stage::Compute};
  in.options.validate = false;
  auto out = compileGlsl(in);
  ASSERT_FALSE(validateSpirv(out.spirv, false)) << "the module as written is valid";
  // The store writes through the buffer variable itself instead of its member's pointer.
  uint32_t bufferVariable = 0;
  size_t storeAt = 0;
  for (size_t i = 5; i < out.spirv.size(); i += out.spirv[i] >> 16) {
    ASSERT_GT(out.spirv[i] >> 16, 0u);
    const uint32_t op = out.spirv[i] & 0xffff;
    if (op == 59 /* OpVariable */ && out.spirv[i + 3] == 12 /* StorageBuffer */)
      bufferVariable = out.spirv[i + 2];
    if (op == 62 /* OpStore */) storeAt = i;
  }
  ASSERT_NE(bufferVariable, 0u);
  ASSERT_NE(storeAt, 0u);
  out.spirv[storeAt + 1] = bufferVariable;
  const auto problem = validateSpirv(out.spirv, false);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("SPIR-V validation (word "), std::string::npos) << *problem;
  EXPECT_NE(problem->find("[%outBuf]"), std::string::npos) << "ids by their names: " << *problem;
}
