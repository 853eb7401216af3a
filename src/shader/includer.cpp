#include "shader/includer.h"

#include "shader/debug_labels.h"
#include "shader/hash.h"

#include <algorithm>

namespace wb::shader {

namespace {
struct Owned {
  std::string name, data;
};
}  // namespace

Includer::Includer(fs::path mainFile, uint64_t mainHash, std::vector<fs::path> roots,
                   const std::map<fs::path, std::string>* overrides)
    : roots_(std::move(roots)), overrides_(overrides) {
  files_.push_back({mainFile, mainHash});
  stack_.push_back(std::move(mainFile));
}

glslang::TShader::Includer::IncludeResult* Includer::includeLocal(const char* h, const char* by, size_t d) {
  return include(h, by, d, true);
}
glslang::TShader::Includer::IncludeResult* Includer::includeSystem(const char* h, const char* by, size_t d) {
  if (!pendingError_.empty() && pendingHeader_ == h) {
    std::string e = std::move(pendingError_);
    pendingError_.clear();
    return fail(std::move(e));
  }
  return include(h, by, d, false);
}

glslang::TShader::Includer::IncludeResult* Includer::fail(std::string message) {
  pendingError_ = message;
  // An empty header name makes glslang report headerData as the error, at the #include line.
  auto* owned = new Owned{"", std::move(message)};
  return new IncludeResult("", owned->data.data(), owned->data.size(), owned);
}

glslang::TShader::Includer::IncludeResult* Includer::include(const char* headerName, const char* includerName,
                                                             size_t depth, bool local) {
  pendingHeader_ = headerName;
  pendingError_.clear();
  const fs::path includer = includerName && *includerName ? fs::path(includerName) : stack_.front();
  // depth is the depth of the file being included (1 for an #include in the main file).
  if (depth >= 1 && depth <= stack_.size()) stack_.resize(depth);
  std::vector<fs::path> candidates;
  const fs::path name(headerName);
  if (name.is_absolute()) {
    candidates.push_back(name);
  } else {
    if (local) candidates.push_back(includer.parent_path() / name);
    for (const auto& r : roots_) candidates.push_back(r / name);
  }
  std::error_code ec;
  for (const auto& c : candidates) {
    if (!fs::is_regular_file(c, ec)) continue;
    fs::path canon = fs::canonical(c, ec);
    if (ec) continue;
    if (std::find(stack_.begin(), stack_.end(), canon) != stack_.end()) {
      std::string chain;
      for (const auto& s : stack_) chain += s.filename().string() + " -> ";
      return fail("include cycle: " + chain + canon.filename().string() + " (" + canon.string() + ")");
    }
    std::optional<std::string> data;
    if (overrides_) {
      const auto kept = overrides_->find(canon);
      if (kept != overrides_->end()) data = kept->second;
    }
    if (!data) data = readFile(canon);
    if (!data) return fail("cannot read include file " + canon.string());
    const uint64_t h = hash64(*data);
    if (std::none_of(files_.begin(), files_.end(), [&](const File& f) { return f.path == canon; }))
      files_.push_back({canon, h});
    stack_.push_back(canon);
    texts_.push_back(*data);
    includedBy_.try_emplace(canon, Edge{includer, headerName});
    textOf_.try_emplace(canon, *data);
    // glslang reads the file with its wbPrint / wbAssert labels as ids (shader/debug_labels.h).
    auto* owned = new Owned{canon.string(), replaceDebugLabels(*data)};
    return new IncludeResult(owned->name, owned->data.data(), owned->data.size(), owned);
  }
  std::string searched;
  for (const auto& c : candidates) searched += (searched.empty() ? "" : ", ") + c.lexically_normal().string();
  return fail("include file not found: \"" + std::string(headerName) + "\" (searched: " + searched + ")");
}

size_t Includer::lineCount(const fs::path& file) const {
  const auto it = textOf_.find(file);
  if (it == textOf_.end()) return 0;
  const std::string& t = it->second;
  const size_t newlines = static_cast<size_t>(std::count(t.begin(), t.end(), '\n'));
  return newlines + (!t.empty() && t.back() != '\n' ? 1 : 0);
}

int Includer::includeLine(const fs::path& file, const std::string& header) const {
  const auto it = textOf_.find(file);
  if (it == textOf_.end() || header.empty()) return 0;
  int number = 0;
  size_t start = 0;
  const std::string& t = it->second;
  while (start <= t.size()) {
    const size_t end = std::min(t.find('\n', start), t.size());
    ++number;
    const std::string line = t.substr(start, end - start);
    if (line.find("#include") != std::string::npos && line.find(header) != std::string::npos) return number;
    start = end + 1;
  }
  return 0;
}

std::string Includer::includeChain(const fs::path& file) const {
  std::string chain;
  fs::path at = file;
  for (int guard = 0; guard < 64; ++guard) {
    const auto it = includedBy_.find(at);
    if (it == includedBy_.end()) break;
    const Edge& e = it->second;
    chain += (chain.empty() ? "" : " <- ") + e.includer.string() + ":" +
             std::to_string(includeLine(e.includer, e.header));
    at = e.includer;
  }
  return chain;
}

bool Includer::mentions(const std::string& word) const {
  return std::any_of(texts_.begin(), texts_.end(),
                     [&](const std::string& t) { return t.find(word) != std::string::npos; });
}

void Includer::releaseInclude(IncludeResult* r) {
  if (!r) return;
  delete static_cast<Owned*>(r->userData);
  delete r;
}

}  // namespace wb::shader
