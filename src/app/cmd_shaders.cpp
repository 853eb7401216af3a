#include "app/cmd_shaders.h"

#include "common/json_text.h"
#include "common/paths.h"
#include "shader/library.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace wb::app {

namespace fs = std::filesystem;
using namespace wb::shader;

namespace {

std::vector<fs::path> collect(const std::vector<std::string>& paths, std::vector<std::string>& errors) {
  std::vector<fs::path> out;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> found;
      for (auto it = fs::recursive_directory_iterator(p, ec); !ec && it != fs::recursive_directory_iterator();
           it.increment(ec))
        if (it->is_regular_file() && stageFromPath(it->path())) found.push_back(it->path());
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::exists(p, ec)) {
      out.emplace_back(p);
    } else {
      errors.push_back(p + ":0: error: no such file or directory");
    }
  }
  return out;
}

nlohmann::json bindingJson(const DescriptorBinding& b) {
  return {{"set", b.set},     {"binding", b.binding},           {"type", descriptorTypeName(b.type)},
          {"count", b.count}, {"runtimeArray", b.runtimeArray}, {"stages", stageFlagsToString(b.stages)},
          {"name", b.name}};
}

}  // namespace

void ShadersCommand::addFlags(CLI::App& app) {
  app.add_option("--define,-D", defines, "preprocessor define K=V (or K)");
  app.add_flag("--json", json, "machine-readable output on stdout");
  app.add_flag("--no-cache", noCache, "do not use the disk cache");
  app.add_flag("--optimize,-O", optimize, "run the SPIR-V optimizer");
  app.add_option("paths", paths, "shader files or directories")->required();
}

int runShadersCommand(const std::vector<std::string>& args) {
  ShadersCommand c;
  return runCommand(c, args);
}

int ShadersCommand::run() {
  std::vector<Define> defs;
  try {
    for (const auto& d : defines) defs.push_back(parseDefine(d, "--define"));
  } catch (const std::invalid_argument& e) {
    std::cerr << "workbench shaders: error: " << e.what() << '\n';
    return 2;
  }
  std::vector<std::string> errors;
  const auto files = collect(paths, errors);
  if (files.empty() && errors.empty()) errors.push_back("no shader files (known stage extensions) found");

  // One library per include-root set: the file's directory + shaders/.
  const fs::path cacheDir = noCache ? fs::path() : shaderCacheDir();
  std::map<fs::path, std::unique_ptr<ShaderLibrary>> libs;
  nlohmann::json out = nlohmann::json::array();
  int failures = static_cast<int>(errors.size());
  for (const auto& e : errors) std::cerr << e << '\n';
  for (const auto& f : files) {
    const fs::path dir = fs::absolute(f).parent_path();
    auto& lib = libs[dir];
    if (!lib)
      lib = std::make_unique<ShaderLibrary>(ShaderLibrary::Options{
          .includeRoots = {dir, shaderDir()}, .cacheDir = cacheDir, .optimize = optimize});
    nlohmann::json j = {{"file", f.string()}};
    try {
      auto s = lib->compile({f, std::nullopt, defs});
      j["stage"] = stageName(s->stage);
      j["ok"] = true;
      j["status"] = "ok";
      j["ms"] = s->compileMs;
      j["cache"] = s->cacheHit ? "hit" : "miss";
      j["spirvBytes"] = s->spirv.size() * 4;
      j["bindings"] = nlohmann::json::array();
      for (const auto& b : s->reflection.bindings) j["bindings"].push_back(bindingJson(b));
      j["pushConstants"] = nlohmann::json::array();
      for (const auto& p : s->reflection.pushConstants)
        j["pushConstants"].push_back(
            {{"offset", p.offset}, {"size", p.size}, {"stages", stageFlagsToString(p.stageFlags)}});
      j["warnings"] = nlohmann::json::array();
      for (const auto& w : s->warnings) {
        j["warnings"].push_back(w.toString());
        if (!json) std::cerr << w.toString() << '\n';
      }
      if (!json) {
        std::printf("%-60s %-6s ok   %8.2f ms  %s\n", f.string().c_str(), stageName(s->stage), s->compileMs,
                    s->cacheHit ? "cache hit" : "cache miss");
        for (const auto& b : s->reflection.bindings) {
          std::string arr = b.runtimeArray ? "[]" : (b.count != 1 ? "[" + std::to_string(b.count) + "]" : "");
          std::printf("    set %u binding %-2u %-24s %s%s\n", b.set, b.binding, descriptorTypeName(b.type),
                      b.name.c_str(), arr.c_str());
        }
        for (const auto& p : s->reflection.pushConstants)
          std::printf("    push constants offset %u size %u\n", p.offset, p.size);
      }
    } catch (const CompileError& e) {
      ++failures;
      auto st = stageFromPath(f);
      j["stage"] = st ? stageName(*st) : "?";
      j["ok"] = false;
      j["status"] = "error";
      j["diagnostics"] = nlohmann::json::array();
      for (const auto& d : e.diagnostics) {
        j["diagnostics"].push_back({{"file", d.file.string()},
                                    {"line", d.line},
                                    {"severity", d.severity},
                                    {"message", d.message},
                                    {"stages", d.stages},
                                    {"included_from", d.includedFrom}});
        std::cerr << d.toString() << '\n';
      }
      if (!json) std::printf("%-60s %-6s FAILED\n", f.string().c_str(), st ? stageName(*st) : "?");
    }
    out.push_back(std::move(j));
  }
  if (json) std::cout << jsonText(out, 2) << '\n';
  if (!json) {
    ShaderLibrary::Stats total{};
    for (const auto& [d, l] : libs) {
      auto s = l->stats();
      total.hits += s.hits;
      total.misses += s.misses;
      total.compiles += s.compiles;
      total.compileMs += s.compileMs;
    }
    std::printf("%zu files, %d failed; cache: %llu hits, %llu misses; glslang %.1f ms\n", files.size(),
                failures, static_cast<unsigned long long>(total.hits),
                static_cast<unsigned long long>(total.misses), total.compileMs);
  }
  return failures ? 1 : 0;
}

}  // namespace wb::app
