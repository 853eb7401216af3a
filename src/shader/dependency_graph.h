// Include graph: which programs depend on which files. Stages are identified by an opaque string (the
// variant key); a program is a list of stages; a stage depends on its file and everything it includes.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace wb::shader {

namespace fs = std::filesystem;

class DependencyGraph {
 public:
  using ProgramId = uint32_t;
  void setStageFiles(const std::string& stage, std::vector<fs::path> files);  // replaces the previous set
  void setProgramStages(ProgramId program, std::vector<std::string> stages);
  std::vector<ProgramId> programsDependingOn(const fs::path& canonicalFile) const;  // sorted
  std::vector<std::string> stagesDependingOn(const fs::path& canonicalFile) const;
  std::vector<fs::path> filesOf(ProgramId program) const;  // sorted, unique
  std::vector<fs::path> allFiles() const;

 private:
  std::map<std::string, std::vector<fs::path>> stageFiles_;
  std::map<fs::path, std::set<std::string>> fileToStages_;
  std::map<ProgramId, std::vector<std::string>> programStages_;
};

}  // namespace wb::shader
