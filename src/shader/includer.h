// glslang TShader::Includer for GL_GOOGLE_include_directive: "x" relative to the including file, then the
// include roots; <x> the include roots only. Records every file read (canonical path + content hash) and
// turns include cycles and missing includes into clear errors at the #include line.
#pragma once
#include <glslang/Public/ShaderLang.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace wb::shader {

namespace fs = std::filesystem;

class Includer : public glslang::TShader::Includer {
 public:
  struct File {
    fs::path path;  // canonical
    uint64_t contentHash;
  };
  // overrides (optional, must outlive the includer): texts read instead of these canonical files.
  Includer(fs::path mainFile, uint64_t mainHash, std::vector<fs::path> roots,
           const std::map<fs::path, std::string>* overrides = nullptr);

  IncludeResult* includeLocal(const char* headerName, const char* includerName, size_t depth) override;
  IncludeResult* includeSystem(const char* headerName, const char* includerName, size_t depth) override;
  void releaseInclude(IncludeResult* r) override;

  const std::vector<File>& files() const { return files_; }  // main file first, then first-seen order
  bool mentions(const std::string& word) const;              // does any included file's text contain word
  // "/inc.glsl:3 <- /main.rchit:5": the #include lines that first brought `file` in, back to the main file
  // ("" for the main file or a file never included).
  std::string includeChain(const fs::path& file) const;
  // Lines of a file read for this compile (the main file's from mainText), 0 when unknown.
  size_t lineCount(const fs::path& file) const;
  // The line of `file` whose #include names `header`, 0 when not found.
  int includeLine(const fs::path& file, const std::string& header) const;
  void setMainText(std::string text) { textOf_[stack_.front()] = std::move(text); }

 private:
  IncludeResult* include(const char* headerName, const char* includerName, size_t depth, bool local);
  IncludeResult* fail(std::string message);
  std::vector<fs::path> roots_;
  const std::map<fs::path, std::string>* overrides_ = nullptr;
  std::vector<File> files_;
  std::vector<std::string> texts_;
  // glslang retries a failed "local" include as a <system> one; keep the first (more precise) error.
  std::string pendingHeader_, pendingError_;
  std::vector<fs::path> stack_;  // stack_[0] = main file, stack_[d] = file at include depth d
  struct Edge {
    fs::path includer;
    std::string header;  // as written in the #include
  };
  std::map<fs::path, Edge> includedBy_;     // first inclusion of each file
  std::map<fs::path, std::string> textOf_;  // every file read, by canonical path
};

}  // namespace wb::shader
