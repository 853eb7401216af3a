#include "shader/dependency_graph.h"

#include <algorithm>

namespace wb::shader {

void DependencyGraph::setStageFiles(const std::string& stage, std::vector<fs::path> files) {
  auto it = stageFiles_.find(stage);
  if (it != stageFiles_.end()) {
    for (const auto& f : it->second) {
      auto ft = fileToStages_.find(f);
      if (ft == fileToStages_.end()) continue;
      ft->second.erase(stage);
      if (ft->second.empty()) fileToStages_.erase(ft);
    }
  }
  for (const auto& f : files) fileToStages_[f].insert(stage);
  stageFiles_[stage] = std::move(files);
}

void DependencyGraph::setProgramStages(ProgramId program, std::vector<std::string> stages) {
  programStages_[program] = std::move(stages);
}

std::vector<std::string> DependencyGraph::stagesDependingOn(const fs::path& file) const {
  auto it = fileToStages_.find(file);
  if (it == fileToStages_.end()) return {};
  return {it->second.begin(), it->second.end()};
}

std::vector<DependencyGraph::ProgramId> DependencyGraph::programsDependingOn(const fs::path& file) const {
  std::vector<ProgramId> out;
  auto it = fileToStages_.find(file);
  if (it == fileToStages_.end()) return out;
  for (const auto& [pid, stages] : programStages_) {
    for (const auto& s : stages) {
      if (it->second.count(s)) {
        out.push_back(pid);
        break;
      }
    }
  }
  return out;
}

std::vector<fs::path> DependencyGraph::filesOf(ProgramId program) const {
  std::set<fs::path> files;
  auto it = programStages_.find(program);
  if (it == programStages_.end()) return {};
  for (const auto& s : it->second) {
    auto sf = stageFiles_.find(s);
    if (sf != stageFiles_.end()) files.insert(sf->second.begin(), sf->second.end());
  }
  return {files.begin(), files.end()};
}

std::vector<fs::path> DependencyGraph::allFiles() const {
  std::vector<fs::path> out;
  for (const auto& [f, s] : fileToStages_) out.push_back(f);
  return out;
}

}  // namespace wb::shader
