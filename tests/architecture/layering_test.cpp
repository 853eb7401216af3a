// The layering of src/ as docs/ARCHITECTURE.md declares it (its table "| folder | may include |"): every
// quoted include of every source file names a header of its own folder or of a folder its row allows, no
// include climbs out with "../", and no two files include each other (a header and its .cpp count as one
// file: "render_inspect" includes "cmd_render" when either of its files includes the other's header).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = WB_SOURCE_DIR;

// folder -> folders it may include, from the architecture document.
std::map<std::string, std::set<std::string>> layerTable() {
  std::ifstream in(kRoot / "docs/ARCHITECTURE.md");
  std::map<std::string, std::set<std::string>> table;
  std::string line;
  bool inTable = false;
  const std::regex row(R"(^\|\s*`?([a-z_]+)`?\s*\|([^|]*)\|)");
  while (std::getline(in, line)) {
    if (line.rfind("| folder | may include |", 0) == 0) {
      inTable = true;
      continue;
    }
    if (!inTable) continue;
    if (line.empty() || line[0] != '|') break;
    std::smatch m;
    if (!std::regex_search(line, m, row)) continue;
    std::set<std::string> allowed{m[1].str()};
    std::stringstream cells(m[2].str());
    std::string word;
    while (cells >> word) {
      word.erase(std::remove_if(word.begin(), word.end(), [](char c) { return c == '`' || c == ','; }),
                 word.end());
      if (!word.empty() && word != "-") allowed.insert(word);
    }
    table[m[1].str()] = allowed;
  }
  return table;
}

struct Include {
  fs::path file;
  int line = 0;
  std::string target;  // as written
};

std::vector<Include> sourceIncludes() {
  std::vector<Include> out;
  const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
  for (const auto& e : fs::recursive_directory_iterator(kRoot / "src")) {
    const auto ext = e.path().extension();
    if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
    std::ifstream in(e.path());
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      std::smatch m;
      if (std::regex_search(line, m, quoted)) out.push_back({e.path(), n, m[1].str()});
    }
  }
  return out;
}

std::string where(const Include& i) {
  return fs::relative(i.file, kRoot).string() + ":" + std::to_string(i.line) + ": #include \"" + i.target +
         "\"";
}

// The folder of src/ a file is in ("render" for src/render/hybrid/x.cpp).
std::string folderOf(const fs::path& file) {
  return fs::relative(file, kRoot / "src").begin()->string();
}

}  // namespace

TEST(Layering, TheArchitectureDocumentDeclaresEveryFolder) {
  const auto table = layerTable();
  ASSERT_FALSE(table.empty()) << "docs/ARCHITECTURE.md has no \"| folder | may include |\" table";
  for (const auto& e : fs::directory_iterator(kRoot / "src")) {
    if (e.is_directory()) {
      EXPECT_TRUE(table.count(e.path().filename().string())) << e.path().filename();
    }
  }
}

TEST(Layering, EveryIncludeFollowsTheLayerTable) {
  const auto table = layerTable();
  std::set<std::string> folders;
  for (const auto& e : fs::directory_iterator(kRoot / "src"))
    if (e.is_directory()) folders.insert(e.path().filename().string());
  for (const auto& i : sourceIncludes()) {
    EXPECT_EQ(i.target.find(".."), std::string::npos) << where(i) << ": includes climb out of the folder";
    const auto slash = i.target.find('/');
    if (slash == std::string::npos) continue;  // a header beside the file
    const std::string target = i.target.substr(0, slash);
    if (!folders.count(target)) continue;  // shaders/ (shared, display) and third-party headers
    const std::string from = folderOf(i.file);
    const auto row = table.find(from);
    ASSERT_NE(row, table.end()) << from << " is not in the layer table";
    EXPECT_TRUE(row->second.count(target)) << where(i) << ": " << from << " may not include " << target;
  }
}

TEST(Layering, NoTwoFilesIncludeEachOther) {
  // Nodes: src/<path without extension>; an edge for each include of another node's header.
  std::map<std::string, std::set<std::string>> edges;
  std::map<std::pair<std::string, std::string>, std::string> example;
  for (const auto& i : sourceIncludes()) {
    const fs::path header =
        fs::exists(kRoot / "src" / i.target) ? kRoot / "src" / i.target : i.file.parent_path() / i.target;
    if (!fs::exists(header)) continue;
    auto node = [](const fs::path& p) { return fs::relative(p, kRoot / "src").replace_extension().string(); };
    const std::string a = node(i.file), b = node(header);
    if (a == b) continue;
    edges[a].insert(b);
    example.emplace(std::make_pair(a, b), where(i));
  }
  // Depth-first search for a cycle, reported as its chain of includes.
  std::map<std::string, int> state;  // 0 new, 1 on the stack, 2 done
  std::vector<std::string> stack;
  std::function<void(const std::string&)> visit = [&](const std::string& n) {
    state[n] = 1;
    stack.push_back(n);
    for (const auto& m : edges[n]) {
      if (state[m] == 1) {
        std::string chain;
        auto it = std::find(stack.begin(), stack.end(), m);
        for (; it != stack.end(); ++it) {
          const auto next = (it + 1 == stack.end()) ? m : *(it + 1);
          chain += "\n  " + example[{*it, next}];
        }
        ADD_FAILURE() << "files that include each other:" << chain;
      } else if (state[m] == 0) {
        visit(m);
      }
    }
    stack.pop_back();
    state[n] = 2;
  };
  for (const auto& [n, _] : edges)
    if (state[n] == 0) visit(n);
}
