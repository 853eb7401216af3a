// ShaderLibrary: cached, thread-safe GLSL compiles (memory + disk), program registry and include graph.
#pragma once
#include "shader/cache.h"
#include "shader/compiler.h"
#include "shader/dependency_graph.h"
#include "shader/hash.h"
#include "shader/reflection.h"
#include "shader/types.h"

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>

namespace wb::shader {

// One diagnostic per place and message: a message that several stages met (an error in a file they all
// include) is kept once, with every stage in Diagnostic::stages.
std::vector<Diagnostic> mergeStageDiagnostics(std::vector<Diagnostic> diags);

class ShaderLibrary {
 public:
  struct Options {
    std::vector<fs::path> includeRoots;
    fs::path cacheDir;  // empty = memory only
    bool optimize = false;
    bool validate = true;
    bool printWarnings = true;  // cache warnings also go to stderr
  };
  explicit ShaderLibrary(Options);
  const Options& options() const { return options_; }
  ~ShaderLibrary();

  // Throws CompileError; thread-safe. Unchanged inputs return the same shared object as last time.
  std::shared_ptr<const CompiledShader> compile(const ShaderKey& key);

  struct Stats {
    uint64_t hits = 0;      // memory or disk
    uint64_t misses = 0;    // needed a glslang compile
    uint64_t compiles = 0;  // glslang compiles run (failed ones included)
    double compileMs = 0;   // total glslang + validation time
  };
  Stats stats() const;
  // Cache problems (corrupt entries, unwritable directory), in order. Also printed to stderr.
  std::vector<std::string> cacheWarnings() const;
  bool diskCacheEnabled() const { return disk_.enabled(); }

  using ProgramId = uint32_t;
  ProgramId registerProgram(std::string name, std::vector<ShaderKey> stages);
  struct ProgramBuild {
    std::vector<std::shared_ptr<const CompiledShader>> stages;  // in registration order
    PipelineLayoutDesc layout;
  };
  // Compiles (cached) all stages, merges layouts. Throws CompileError with the diagnostics of every failing
  // stage.
  ProgramBuild buildProgram(ProgramId id);
  std::vector<ProgramId> programsDependingOn(const fs::path& file) const;  // via the include graph
  std::vector<ProgramId> programs() const;
  std::string programName(ProgramId id) const;
  std::vector<ShaderKey> programStages(ProgramId id) const;
  std::optional<bool> programOk(ProgramId id) const;  // nullopt = never built

  struct FileStatus {
    bool ok = true;
    std::vector<Diagnostic> diagnostics;  // errors when !ok, else warnings
    double lastCompileMs = 0;
    bool lastCacheHit = false;
    std::vector<std::string> programs;
  };
  // Keyed by canonical path: every compiled stage file, and included files that have diagnostics.
  std::map<fs::path, FileStatus> fileStatuses() const;

  // Forget cached stat information for these files (the watcher saw them change), and the texts kept for
  // them.
  void invalidateFiles(const std::vector<fs::path>& files);

  // A revert (the A/B panel's): until a file's next change on disk (invalidateFiles), compiles read the text
  // these stages were compiled from instead of the file, so that what is built later (a variant: the cost
  // view, the inspector, asserts) is the reverted code and not the edit on disk. Returns the files whose text
  // is no longer known (their compiles read the file on disk).
  std::vector<fs::path> keepSourcesOf(const std::vector<std::shared_ptr<const CompiledShader>>& stages);
  std::vector<fs::path> keptSources() const;  // the files read from kept texts now

 private:
  struct MemEntry {
    std::shared_ptr<const CompiledShader> shader;
    std::vector<uint64_t> hashes;  // parallel to shader->files
  };
  struct Program {
    std::string name;
    std::vector<ShaderKey> stages;
    std::vector<std::string> stageIds;
    std::optional<bool> ok;
  };
  struct Resolved {
    fs::path path;
    Stage stage;
    Hash128 variant;
  };
  Resolved resolve(const ShaderKey& key) const;
  // A file's content hash as compiles see it: its kept text's, else the file's (hashes_).
  std::optional<uint64_t> currentHash(const fs::path& file);
  std::optional<Hash128> contentKey(const Hash128& variant, const std::vector<fs::path>& files,
                                    std::vector<uint64_t>* hashes);
  void warn(const std::string& w);
  void markIncludesOk(const CompiledShader& s);
  void recordStatus(const fs::path& file, const std::vector<Diagnostic>& diags, bool ok, double ms, bool hit);

  // The steps of compile(): the memory cache, the disk cache, glslang; remember() keeps what the last two
  // give in memory and records the stage's status.
  std::shared_ptr<const CompiledShader> fromMemory(const Resolved& r, const std::string& vid);
  std::optional<MemEntry> fromDisk(const ShaderKey& key, const Resolved& r,
                                   std::chrono::steady_clock::time_point t0);
  MemEntry compileNew(const ShaderKey& key, const Resolved& r, const std::string& vid,
                      std::chrono::steady_clock::time_point t0);
  // glslang on the stage's file; a failure is counted and recorded before it is rethrown.
  CompileOutput runGlslang(const ShaderKey& key, const Resolved& r, const std::string& vid,
                           std::chrono::steady_clock::time_point t0);
  void recordFailedCompile(const Resolved& r, const std::string& vid, const std::vector<Diagnostic>& diags,
                           double ms);
  // A compiled stage from its SPIR-V, reflected.
  std::shared_ptr<CompiledShader> makeShader(const ShaderKey& key, const Resolved& r,
                                             std::vector<uint32_t> spirv, std::vector<fs::path> files,
                                             std::vector<Diagnostic> warnings, bool cacheHit) const;
  void storeOnDisk(const Resolved& r, const CompileOutput& out, const CompiledShader& s);
  std::shared_ptr<const CompiledShader> remember(const std::string& vid, const fs::path& path,
                                                 MemEntry entry);

  Options options_;
  FileHashCache hashes_;
  mutable std::mutex warnMutex_;
  std::vector<std::string> warnings_;
  DiskCache disk_;
  mutable std::mutex mutex_;
  Stats stats_;
  std::unordered_map<std::string, MemEntry> memory_;
  DependencyGraph graph_;
  std::vector<Program> programs_;
  std::map<fs::path, FileStatus> statuses_;
  std::map<fs::path, std::string> kept_;  // keepSourcesOf's texts, by canonical path
};

}  // namespace wb::shader
