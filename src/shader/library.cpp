#include "shader/library.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <set>

namespace wb::shader {

namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

ShaderLibrary::ShaderLibrary(Options o)
    : options_(std::move(o)), disk_(options_.cacheDir, [this](const std::string& w) { warn(w); }) {
  for (auto& r : options_.includeRoots) {
    std::error_code ec;
    auto c = fs::weakly_canonical(r, ec);
    if (!ec) r = c;
  }
}

ShaderLibrary::~ShaderLibrary() = default;

void ShaderLibrary::warn(const std::string& w) {
  if (options_.printWarnings) std::cerr << "warning: " << w << '\n';
  std::lock_guard lock(warnMutex_);
  warnings_.push_back(w);
}

std::vector<std::string> ShaderLibrary::cacheWarnings() const {
  std::lock_guard lock(warnMutex_);
  return warnings_;
}

ShaderLibrary::Stats ShaderLibrary::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

ShaderLibrary::Resolved ShaderLibrary::resolve(const ShaderKey& key) const {
  std::error_code ec;
  fs::path path = fs::canonical(key.path, ec);
  if (ec || !fs::is_regular_file(path))
    throw CompileError({{fs::absolute(key.path).lexically_normal(), 0, "error", "shader file not found"}});
  std::optional<Stage> stage = key.stage ? key.stage : stageFromPath(path);
  if (!stage)
    throw CompileError(
        {{path, 0, "error",
          "unknown shader stage (use .rgen .rmiss .rchit .rahit .rint .rcall .vert .frag .comp or "
          "name.<stage>.glsl, or set ShaderKey::stage)"}});
  for (const auto& d : key.defines) {
    if (const std::string problem = defineProblem(d); !problem.empty())
      throw CompileError({{path, 0, "error", "define: " + problem}});
  }
  Hasher h;
  h.add(uint64_t{DiskCache::kFormatVersion}).add(compilerFingerprint()).add(path.string());
  h.add(uint64_t(static_cast<int>(*stage))).add(key.entry);
  h.add(uint64_t(key.defines.size()));
  for (const auto& d : key.defines) h.add(d.name).add(d.value);
  h.add(uint64_t(options_.optimize)).add(uint64_t(options_.validate));
  h.add(uint64_t(options_.includeRoots.size()));
  for (const auto& r : options_.includeRoots) h.add(r.string());
  return {path, *stage, h.finish()};
}

std::optional<uint64_t> ShaderLibrary::currentHash(const fs::path& file) {
  {
    std::lock_guard lock(mutex_);
    const auto it = kept_.find(file);
    if (it != kept_.end()) return hash64(it->second);
  }
  return hashes_.hash(file);
}

std::optional<Hash128> ShaderLibrary::contentKey(const Hash128& variant, const std::vector<fs::path>& files,
                                                 std::vector<uint64_t>* hashes) {
  Hasher h;
  h.add(variant.lo).add(variant.hi);
  for (const auto& f : files) {
    auto fh = currentHash(f);
    if (!fh) return std::nullopt;  // a dependency vanished: must recompile (and fail properly)
    h.add(f.string()).add(*fh);
    if (hashes) hashes->push_back(*fh);
  }
  return h.finish();
}

void ShaderLibrary::recordStatus(const fs::path& file, const std::vector<Diagnostic>& diags, bool ok,
                                 double ms, bool hit) {
  std::lock_guard lock(mutex_);
  auto& st = statuses_[file];
  st.ok = ok;
  st.diagnostics.clear();
  st.lastCompileMs = ms;
  st.lastCacheHit = hit;
  for (const auto& d : diags) {
    if (d.file == file || d.file.empty()) {
      st.diagnostics.push_back(d);
    } else {
      // Keep included files' messages under their own file too.
      auto& inc = statuses_[d.file];
      if (inc.ok || !ok) inc.diagnostics.clear();
      inc.ok = ok ? inc.ok : false;
      inc.diagnostics.push_back(d);
      st.diagnostics.push_back(d);
    }
  }
}

void ShaderLibrary::markIncludesOk(const CompiledShader& s) {
  // Included files compiled cleanly now (caller holds mutex_).
  for (size_t i = 1; i < s.files.size(); ++i) {
    auto it = statuses_.find(s.files[i]);
    if (it != statuses_.end() && !it->second.ok) {
      it->second.ok = true;
      it->second.diagnostics.clear();
    }
  }
}

std::shared_ptr<const CompiledShader> ShaderLibrary::compile(const ShaderKey& key) {
  const auto t0 = std::chrono::steady_clock::now();
  Resolved r;
  try {
    r = resolve(key);
  } catch (const CompileError& e) {
    recordStatus(e.diagnostics.front().file, e.diagnostics, false, 0, false);
    throw;
  }
  const std::string vid = r.variant.hex();
  if (auto cached = fromMemory(r, vid)) return cached;
  if (auto loaded = fromDisk(key, r, t0)) return remember(vid, r.path, std::move(*loaded));
  return remember(vid, r.path, compileNew(key, r, vid, t0));
}

std::shared_ptr<const CompiledShader> ShaderLibrary::fromMemory(const Resolved& r, const std::string& vid) {
  // Same files with the same contents as last time -> the same object.
  std::shared_ptr<const CompiledShader> cached;
  std::vector<uint64_t> expected;
  {
    std::lock_guard lock(mutex_);
    auto it = memory_.find(vid);
    if (it == memory_.end()) return nullptr;
    cached = it->second.shader;
    expected = it->second.hashes;
  }
  for (size_t i = 0; i < cached->files.size(); ++i) {
    auto h = currentHash(cached->files[i]);
    if (!h || *h != expected[i]) return nullptr;
  }
  std::lock_guard lock(mutex_);
  ++stats_.hits;
  // A failed compile in between registered the files it touched; the stage depends on these again.
  graph_.setStageFiles(vid, cached->files);
  auto& st = statuses_[r.path];
  st.ok = true;
  st.diagnostics = cached->warnings;
  st.lastCacheHit = true;
  st.lastCompileMs = 0;
  markIncludesOk(*cached);
  return cached;
}

std::optional<ShaderLibrary::MemEntry> ShaderLibrary::fromDisk(const ShaderKey& key, const Resolved& r,
                                                               std::chrono::steady_clock::time_point t0) {
  // The index gives the dependency list; the content key is recomputed from current contents.
  if (!disk_.enabled()) return std::nullopt;
  auto deps = disk_.loadIndex(r.variant);
  if (!deps || deps->front() != r.path) return std::nullopt;
  std::vector<uint64_t> hashes;
  auto k = contentKey(r.variant, *deps, &hashes);
  if (!k) return std::nullopt;
  auto entry = disk_.load(*k);
  if (!entry || entry->files != *deps) return std::nullopt;
  auto s =
      makeShader(key, r, std::move(entry->spirv), std::move(entry->files), std::move(entry->warnings), true);
  s->fileHashes = hashes;
  s->compileMs = msSince(t0);
  try {
    checkBindingAliases(*s);  // entries written before this check existed
  } catch (const CompileError& e) {
    recordStatus(r.path, e.diagnostics, false, s->compileMs, true);
    throw;
  }
  {
    std::lock_guard lock(mutex_);
    ++stats_.hits;
  }
  return MemEntry{std::move(s), std::move(hashes)};
}

ShaderLibrary::MemEntry ShaderLibrary::compileNew(const ShaderKey& key, const Resolved& r,
                                                  const std::string& vid,
                                                  std::chrono::steady_clock::time_point t0) {
  CompileOutput out = runGlslang(key, r, vid, t0);
  auto s = makeShader(key, r, std::move(out.spirv), out.files, std::move(out.warnings), false);
  s->fileHashes = out.contentHashes;
  s->compileMs = out.ms;
  // Each file's text is then known by its hash (FileHashCache keeps the texts it read), for keepSourcesOf.
  for (const auto& f : out.files) currentHash(f);
  {
    std::lock_guard lock(mutex_);
    ++stats_.misses;
    ++stats_.compiles;
    stats_.compileMs += out.ms;
  }
  try {
    checkBindingAliases(*s);  // glslang accepts two descriptor types at one binding; a pipeline layout cannot
  } catch (const CompileError& e) {
    {
      std::lock_guard lock(mutex_);
      graph_.setStageFiles(vid, s->files);
    }
    recordStatus(r.path, e.diagnostics, false, out.ms, false);
    throw;
  }
  if (disk_.enabled()) storeOnDisk(r, out, *s);
  return MemEntry{std::move(s), std::move(out.contentHashes)};
}

CompileOutput ShaderLibrary::runGlslang(const ShaderKey& key, const Resolved& r, const std::string& vid,
                                        std::chrono::steady_clock::time_point t0) {
  CompileInput in;
  in.path = r.path;
  {
    std::lock_guard lock(mutex_);
    in.sourceOverrides = kept_;
  }
  const auto kept = in.sourceOverrides.find(r.path);
  auto source =
      kept != in.sourceOverrides.end() ? std::optional<std::string>(kept->second) : readFile(r.path);
  if (!source) throw CompileError({{r.path, 0, "error", "cannot read shader file"}});
  in.source = std::move(*source);
  in.stage = r.stage;
  in.defines = key.defines;
  in.entry = key.entry;
  in.includeRoots = options_.includeRoots;
  in.options = {options_.optimize, options_.validate};
  try {
    return compileGlsl(in);
  } catch (const CompileError& e) {
    recordFailedCompile(r, vid, e.diagnostics, msSince(t0));
    throw;
  }
}

void ShaderLibrary::recordFailedCompile(const Resolved& r, const std::string& vid,
                                        const std::vector<Diagnostic>& diags, double ms) {
  {
    std::lock_guard lock(mutex_);
    ++stats_.misses;
    ++stats_.compiles;
    stats_.compileMs += ms;
    // Keep the graph useful while broken: previous files + files named by the errors.
    std::set<fs::path> files{r.path};
    if (auto it = memory_.find(vid); it != memory_.end())
      files.insert(it->second.shader->files.begin(), it->second.shader->files.end());
    for (const auto& d : diags)
      if (!d.file.empty()) files.insert(d.file);
    std::vector<fs::path> list{r.path};
    for (const auto& f : files)
      if (f != r.path) list.push_back(f);
    graph_.setStageFiles(vid, list);
  }
  recordStatus(r.path, diags, false, ms, false);
}

std::shared_ptr<CompiledShader> ShaderLibrary::makeShader(const ShaderKey& key, const Resolved& r,
                                                          std::vector<uint32_t> spirv,
                                                          std::vector<fs::path> files,
                                                          std::vector<Diagnostic> warnings,
                                                          bool cacheHit) const {
  auto s = std::make_shared<CompiledShader>();
  s->key = key;
  s->stage = r.stage;
  s->spirv = std::move(spirv);
  s->files = std::move(files);
  s->warnings = std::move(warnings);
  s->cacheHit = cacheHit;
  s->reflection = reflectSpirv(s->spirv, r.stage, r.path);
  return s;
}

void ShaderLibrary::storeOnDisk(const Resolved& r, const CompileOutput& out, const CompiledShader& s) {
  // The key is built from exactly the bytes glslang compiled.
  Hasher h;
  h.add(r.variant.lo).add(r.variant.hi);
  for (size_t i = 0; i < out.files.size(); ++i) h.add(out.files[i].string()).add(out.contentHashes[i]);
  disk_.store(CacheEntry{h.finish(), s.spirv, s.files, s.warnings});
  disk_.storeIndex(r.variant, s.files);
}

std::shared_ptr<const CompiledShader> ShaderLibrary::remember(const std::string& vid, const fs::path& path,
                                                              MemEntry entry) {
  std::lock_guard lock(mutex_);
  std::shared_ptr<const CompiledShader> s = entry.shader;
  memory_[vid] = std::move(entry);
  graph_.setStageFiles(vid, s->files);
  auto& st = statuses_[path];
  st.ok = true;
  st.diagnostics = s->warnings;
  st.lastCompileMs = s->compileMs;
  st.lastCacheHit = s->cacheHit;
  markIncludesOk(*s);
  return s;
}

std::vector<Diagnostic> mergeStageDiagnostics(std::vector<Diagnostic> diags) {
  std::vector<Diagnostic> out;
  for (auto& d : diags) {
    auto same = std::find_if(out.begin(), out.end(), [&](const Diagnostic& o) {
      return o.file == d.file && o.line == d.line && o.severity == d.severity && o.message == d.message;
    });
    if (same == out.end()) {
      out.push_back(std::move(d));
      continue;
    }
    for (auto& st : d.stages)
      if (std::find(same->stages.begin(), same->stages.end(), st) == same->stages.end())
        same->stages.push_back(st);
    if (same->includedFrom.empty()) same->includedFrom = d.includedFrom;
  }
  return out;
}

ShaderLibrary::ProgramId ShaderLibrary::registerProgram(std::string name, std::vector<ShaderKey> stages) {
  Program p;
  p.name = std::move(name);
  for (const auto& k : stages) {
    std::string id;
    try {
      Resolved r = resolve(k);
      id = r.variant.hex();
      std::lock_guard lock(mutex_);
      if (!memory_.count(id)) graph_.setStageFiles(id, {r.path});
    } catch (const CompileError&) {
      // Missing file or unknown stage: reported by buildProgram. Depend on the path as given.
      id = "unresolved:" + fs::absolute(k.path).lexically_normal().string();
      std::lock_guard lock(mutex_);
      graph_.setStageFiles(id, {fs::absolute(k.path).lexically_normal()});
    }
    p.stageIds.push_back(id);
  }
  p.stages = std::move(stages);
  std::lock_guard lock(mutex_);
  const auto pid = static_cast<ProgramId>(programs_.size());
  graph_.setProgramStages(pid, p.stageIds);
  programs_.push_back(std::move(p));
  return pid;
}

ShaderLibrary::ProgramBuild ShaderLibrary::buildProgram(ProgramId id) {
  std::vector<ShaderKey> keys;
  {
    std::lock_guard lock(mutex_);
    if (id >= programs_.size()) throw std::out_of_range("unknown program id");
    keys = programs_[id].stages;
  }
  ProgramBuild b;
  std::vector<Diagnostic> errors;
  std::vector<std::string> stageIds;
  for (const auto& k : keys) {
    try {
      auto s = compile(k);
      b.stages.push_back(s);
      stageIds.push_back(resolve(k).variant.hex());
    } catch (const CompileError& e) {
      errors.insert(errors.end(), e.diagnostics.begin(), e.diagnostics.end());
      try {
        stageIds.push_back(resolve(k).variant.hex());
      } catch (const CompileError&) {
        stageIds.push_back("unresolved:" + fs::absolute(k.path).lexically_normal().string());
      }
    }
  }
  {
    std::lock_guard lock(mutex_);
    programs_[id].stageIds = stageIds;
    graph_.setProgramStages(id, stageIds);
  }
  if (errors.empty()) {
    try {
      b.layout = mergeLayouts(b.stages);
    } catch (const CompileError& e) {
      errors = e.diagnostics;
      for (const auto& d : e.diagnostics) recordStatus(d.file, {d}, false, 0, false);
    }
  }
  {
    std::lock_guard lock(mutex_);
    programs_[id].ok = errors.empty();
  }
  if (!errors.empty()) throw CompileError(mergeStageDiagnostics(std::move(errors)));
  return b;
}

std::vector<ShaderLibrary::ProgramId> ShaderLibrary::programsDependingOn(const fs::path& file) const {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(file, ec);
  if (ec) p = fs::absolute(file).lexically_normal();
  std::lock_guard lock(mutex_);
  return graph_.programsDependingOn(p);
}

std::vector<ShaderLibrary::ProgramId> ShaderLibrary::programs() const {
  std::lock_guard lock(mutex_);
  std::vector<ProgramId> out;
  for (ProgramId i = 0; i < programs_.size(); ++i) out.push_back(i);
  return out;
}

std::string ShaderLibrary::programName(ProgramId id) const {
  std::lock_guard lock(mutex_);
  return id < programs_.size() ? programs_[id].name : std::string();
}

std::vector<ShaderKey> ShaderLibrary::programStages(ProgramId id) const {
  std::lock_guard lock(mutex_);
  return programs_.at(id).stages;
}

std::optional<bool> ShaderLibrary::programOk(ProgramId id) const {
  std::lock_guard lock(mutex_);
  return id < programs_.size() ? programs_[id].ok : std::nullopt;
}

std::map<fs::path, ShaderLibrary::FileStatus> ShaderLibrary::fileStatuses() const {
  std::lock_guard lock(mutex_);
  auto out = statuses_;
  for (auto& [file, st] : out) {
    st.programs.clear();
    for (auto pid : graph_.programsDependingOn(file)) st.programs.push_back(programs_[pid].name);
  }
  return out;
}

void ShaderLibrary::invalidateFiles(const std::vector<fs::path>& files) {
  for (const auto& f : files) hashes_.invalidate(f);
  std::lock_guard lock(mutex_);
  for (const auto& f : files) kept_.erase(f);
}

std::vector<fs::path> ShaderLibrary::keepSourcesOf(
    const std::vector<std::shared_ptr<const CompiledShader>>& stages) {
  std::vector<fs::path> unknown;
  for (const auto& s : stages) {
    if (!s) continue;
    for (size_t i = 0; i < s->files.size(); ++i) {
      const fs::path& f = s->files[i];
      if (i >= s->fileHashes.size()) {
        if (std::find(unknown.begin(), unknown.end(), f) == unknown.end()) unknown.push_back(f);
        continue;
      }
      const auto onDisk = hashes_.hash(f);
      if (onDisk && *onDisk == s->fileHashes[i]) {
        std::lock_guard lock(mutex_);
        kept_.erase(f);  // the file holds that text (again)
        continue;
      }
      const auto text = hashes_.text(f, s->fileHashes[i]);
      if (!text) {
        if (std::find(unknown.begin(), unknown.end(), f) == unknown.end()) unknown.push_back(f);
        continue;
      }
      std::lock_guard lock(mutex_);
      kept_[f] = *text;
    }
  }
  return unknown;
}

std::vector<fs::path> ShaderLibrary::keptSources() const {
  std::lock_guard lock(mutex_);
  std::vector<fs::path> files;
  for (const auto& [f, text] : kept_) files.push_back(f);
  return files;
}

}  // namespace wb::shader
