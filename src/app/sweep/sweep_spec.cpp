#include "app/sweep/sweep_spec.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>

#include "app/converge_run.h"
#include "common/file_io.h"
#include "common/json_text.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace wb::app::sweep {
namespace {

// Reads one sweep file's JSON into a Sweep, naming the file and the entry in every message.
class SpecReader {
 public:
  SpecReader(std::string source, fs::path base) : source_(std::move(source)), base_(std::move(base)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  void onlyKeys(const json& obj, const std::string& where, const std::vector<std::string>& known) const {
    if (!obj.is_object()) fail(where, "expected an object {...}");
    for (const auto& [key, value] : obj.items()) {
      (void)value;
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      fail(where, "unknown key '" + key + "' (known: " + list + ")");
    }
  }

  std::string string(const json& obj, const std::string& key, const std::string& where,
                     const std::string& fallback) const {
    if (!obj.contains(key)) return fallback;
    if (!obj[key].is_string()) fail(where + "." + key, "expected a string");
    return obj[key].get<std::string>();
  }

  uint32_t count(const json& obj, const std::string& key, const std::string& where, uint32_t fallback,
                 uint32_t lo, uint32_t hi) const {
    if (!obj.contains(key)) return fallback;
    const json& v = obj[key];
    if (!v.is_number_integer() || v.get<int64_t>() < int64_t(lo) || v.get<int64_t>() > int64_t(hi)) {
      fail(where + "." + key, "expected a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                                  ", got " + jsonText(v));
    }
    return uint32_t(v.get<int64_t>());
  }

  // Flags as a string ("--max-bounces 4 --no-mis", quotes group) or an array of strings.
  std::vector<std::string> flags(const json& obj, const std::string& key, const std::string& where) const {
    if (!obj.contains(key)) return {};
    const json& v = obj[key];
    if (v.is_string()) {
      try {
        return splitFlags(v.get<std::string>(), where + "." + key);
      } catch (const std::invalid_argument& e) {
        fail("", e.what());
      }
    }
    if (!v.is_array()) fail(where + "." + key, "expected a string or an array of strings");
    std::vector<std::string> out;
    for (const auto& f : v) {
      if (!f.is_string()) fail(where + "." + key, "expected strings, got " + jsonText(f));
      out.push_back(f.get<std::string>());
    }
    return out;
  }

  std::string name(const json& obj, const std::string& where, const std::string& fallback) const {
    const std::string n = string(obj, "name", where, fallback);
    if (n.empty()) fail(where, "needs a \"name\"");
    for (char c : n) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') {
        fail(where + ".name", "'" + n + "': use letters, digits, - and _ (it names tasks and files)");
      }
    }
    return n;
  }

  // An existing file, relative to the sweep file's folder; returned absolute.
  std::string file(const json& obj, const std::string& key, const std::string& where) const {
    const std::string p = string(obj, key, where, "");
    if (p.empty()) fail(where + "." + key, "empty path");
    fs::path abs = fs::path(p).is_absolute() ? fs::path(p) : base_ / p;
    abs = abs.lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(abs, ec)) {
      fail(where + "." + key, "'" + abs.string() + "' is " + describeFileKind(abs) + ", not a file");
    }
    return abs.string();
  }

  Sweep read(const json& root) const {
    onlyKeys(root, "",
             {"name", "size", "flags", "seeds", "checkpoints", "reference_spp", "target_relmse", "scenes",
              "configs"});
    Sweep s;
    s.name = name(root, "", "sweep");
    s.size = string(root, "size", "size", "");
    if (s.size.empty()) fail("size", "needs the image size, e.g. \"size\": \"64x64\"");
    s.flags = flags(root, "flags", "");
    s.seeds = count(root, "seeds", "", 1, 1, 4096);
    if (!root.contains("checkpoints") || !root["checkpoints"].is_array() || root["checkpoints"].empty()) {
      fail("checkpoints", "needs a list of increasing spp, e.g. [1, 4, 16, 64]");
    }
    for (const auto& c : root["checkpoints"]) {
      if (!c.is_number_integer() || c.get<int64_t>() < 1 || c.get<int64_t>() > (int64_t(1) << 24))
        fail("checkpoints", "expected whole numbers of spp in 1..16777216, got " + jsonText(c));
      const uint32_t spp = uint32_t(c.get<int64_t>());
      if (!s.checkpoints.empty() && spp <= s.checkpoints.back())
        fail("checkpoints",
             "must increase: " + std::to_string(spp) + " after " + std::to_string(s.checkpoints.back()));
      s.checkpoints.push_back(spp);
    }
    const uint32_t referenceSpp = count(root, "reference_spp", "", 1024, 1, 1u << 24);
    if (root.contains("target_relmse")) {
      const json& t = root["target_relmse"];
      if (!t.is_number() || !(t.get<double>() > 0)) fail("target_relmse", "expected a positive number");
      s.targetRelMse = t.get<double>();
    }
    if (!root.contains("scenes") || !root["scenes"].is_array() || root["scenes"].empty())
      fail("scenes", "needs a list of scenes, e.g. [{\"name\": \"default\"}]");
    std::set<std::string> names;
    for (size_t i = 0; i < root["scenes"].size(); ++i) {
      const json& js = root["scenes"][i];
      const std::string where = "scenes[" + std::to_string(i) + "]";
      onlyKeys(js, where, {"name", "path", "flags", "reference", "reference_spp"});
      SceneSpec sc;
      if (js.contains("path")) sc.path = file(js, "path", where);
      sc.name = name(js, where, sc.path.empty() ? "default" : fs::path(sc.path).stem().string());
      if (!names.insert(sc.name).second) fail(where + ".name", "'" + sc.name + "' names two scenes");
      sc.flags = flags(js, "flags", where);
      if (js.contains("reference") && js.contains("reference_spp"))
        fail(where, "give \"reference\" (a file) or \"reference_spp\" (render one), not both");
      if (js.contains("reference")) {
        sc.referenceFile = file(js, "reference", where);
      } else {
        sc.referenceSpp = count(js, "reference_spp", where, referenceSpp, 1, 1u << 24);
      }
      s.scenes.push_back(std::move(sc));
    }
    names.clear();
    const json configs = root.contains("configs") ? root["configs"] : json::array({json{{"name", "base"}}});
    if (!configs.is_array() || configs.empty()) fail("configs", "expected a list of configurations");
    for (size_t i = 0; i < configs.size(); ++i) {
      const json& jc = configs[i];
      const std::string where = "configs[" + std::to_string(i) + "]";
      onlyKeys(jc, where, {"name", "flags", "defines", "mode"});
      ConfigSpec c;
      c.name = name(jc, where, "");
      if (!names.insert(c.name).second) fail(where + ".name", "'" + c.name + "' names two configurations");
      c.flags = flags(jc, "flags", where);
      if (jc.contains("defines")) {
        const json& d = jc["defines"];
        if (d.is_object()) {
          for (const auto& [k, v] : d.items()) {
            if (!v.is_string() && !v.is_number())
              fail(where + ".defines." + k, "expected a string or number");
            c.flags.push_back("--define");
            c.flags.push_back(k + "=" + (v.is_string() ? v.get<std::string>() : v.dump()));
          }
        } else if (d.is_array()) {
          for (const auto& v : d) {
            if (!v.is_string()) fail(where + ".defines", "expected strings NAME=VALUE, got " + jsonText(v));
            c.flags.push_back("--define");
            c.flags.push_back(v.get<std::string>());
          }
        } else {
          fail(where + ".defines", "expected {\"NAME\": \"VALUE\", ...} or [\"NAME=VALUE\", ...]");
        }
      }
      if (jc.contains("mode")) {
        c.flags.push_back("--mode");
        c.flags.push_back(string(jc, "mode", where, ""));
      }
      s.configs.push_back(std::move(c));
    }
    checkFlags(s);
    expand(s);
    return s;
  }

 private:
  // Every scene x configuration parses, and none changes the scene or the size.
  void checkFlags(const Sweep& s) const {
    for (size_t i = 0; i < s.scenes.size(); ++i) {
      const std::string where = "scenes[" + std::to_string(i) + "] (" + s.scenes[i].name + ")";
      RenderOptions base;
      try {
        base = s.sceneOptions(i);
      } catch (const std::exception& e) {
        fail(where, std::string("its flags and the sweep's: ") + e.what());
      }
      if (base.params.render.width == 0) fail("size", "bad size");
      for (size_t k = 0; k < s.configs.size(); ++k) {
        const std::string cwhere = "configs[" + std::to_string(k) + "] (" + s.configs[k].name + ")";
        RenderOptions ro;
        try {
          ro = s.configOptions(i, k);
        } catch (const std::exception& e) {
          fail(cwhere + " on " + where, e.what());
        }
        if (ro.scene != base.scene || ro.params.render.width != base.params.render.width ||
            ro.params.render.height != base.params.render.height) {
          fail(cwhere, "a configuration cannot change the scene or --size");
        }
      }
    }
  }

  static void expand(Sweep& s) {
    for (size_t i = 0; i < s.scenes.size(); ++i) {
      if (!s.scenes[i].referenceFile.empty()) continue;
      Task t;
      t.id = s.scenes[i].name + ".ref";
      t.kind = TaskKind::Reference;
      t.scene = i;
      s.tasks.push_back(t);
    }
    for (size_t i = 0; i < s.scenes.size(); ++i) {
      for (size_t k = 0; k < s.configs.size(); ++k) {
        for (uint32_t seed = 0; seed < s.seeds; ++seed) {
          Task t;
          t.id = s.scenes[i].name + "." + s.configs[k].name + ".s" + std::to_string(seed);
          t.kind = TaskKind::Run;
          t.scene = i;
          t.config = k;
          t.seedIndex = seed;
          s.tasks.push_back(t);
        }
      }
    }
  }

  std::string source_;
  fs::path base_;
};

size_t lineOf(const std::string& text, size_t byte) {
  return size_t(std::count(text.begin(), text.begin() + std::min(byte, text.size()), '\n')) + 1;
}

json flagsJson(const std::vector<std::string>& flags) {
  return json(flags);
}

}  // namespace

namespace {

// The command line of a scene's renders: its file, the size, the sweep's flags and the scene's.
std::vector<std::string> sceneArgs(const Sweep& s, size_t scene) {
  const SceneSpec& sc = s.scenes.at(scene);
  std::vector<std::string> args;
  if (!sc.path.empty()) args.push_back(sc.path);
  args.push_back("--size");
  args.push_back(s.size);
  args.insert(args.end(), s.flags.begin(), s.flags.end());
  args.insert(args.end(), sc.flags.begin(), sc.flags.end());
  return args;
}

}  // namespace

RenderOptions Sweep::sceneOptions(size_t scene) const {
  return parseRenderFlags(sceneArgs(*this, scene));
}

RenderOptions Sweep::configOptions(size_t scene, size_t config) const {
  std::vector<std::string> args = sceneArgs(*this, scene);
  const auto& cf = configs.at(config).flags;
  args.insert(args.end(), cf.begin(), cf.end());
  return parseRenderFlags(args);
}

uint32_t Sweep::taskSeed(const Task& task) const {
  if (task.kind == TaskKind::Reference) return kReferenceSeed;
  return runSeed(configOptions(task.scene, task.config).params.render.seed, task.seedIndex);
}

size_t Sweep::findTask(const std::string& idOrNumber) const {
  for (size_t i = 0; i < tasks.size(); ++i)
    if (tasks[i].id == idOrNumber) return i;
  if (!idOrNumber.empty() && std::all_of(idOrNumber.begin(), idOrNumber.end(), ::isdigit) &&
      idOrNumber.size() < 10 && std::stoul(idOrNumber) < tasks.size()) {
    return std::stoul(idOrNumber);
  }
  throw std::invalid_argument("no task '" + idOrNumber + "' in this sweep (" + std::to_string(tasks.size()) +
                              " tasks: `workbench sweep status DIR` lists them)");
}

long Sweep::referenceTask(size_t scene) const {
  for (size_t i = 0; i < tasks.size(); ++i)
    if (tasks[i].kind == TaskKind::Reference && tasks[i].scene == scene) return long(i);
  return -1;
}

size_t Sweep::referenceCount() const {
  return size_t(
      std::count_if(tasks.begin(), tasks.end(), [](const Task& t) { return t.kind == TaskKind::Reference; }));
}

Sweep parseSpec(const std::string& text, const std::string& source, const fs::path& base) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const auto colon = what.find("]: ");  // "[json.exception.parse_error.101] parse error at line 3, ..."
    if (colon != std::string::npos) what = what.substr(colon + 3);
    throw std::invalid_argument(source + ": line " + std::to_string(lineOf(text, e.byte)) +
                                ": not valid JSON: " + what);
  }
  return SpecReader(source, base).read(root);
}

Sweep readSpec(const fs::path& file) {
  std::string why;
  const auto text = readRegularFile(file, &why, 64u << 20);
  if (!text) throw std::invalid_argument("sweep file '" + file.string() + "': " + why);
  std::error_code ec;
  const fs::path abs = fs::absolute(file, ec).lexically_normal();
  Sweep s = parseSpec(*text, file.string(), abs.parent_path());
  s.specFile = abs.string();
  return s;
}

json toJson(const Sweep& s) {
  json j;
  j["name"] = s.name;
  j["size"] = s.size;
  j["flags"] = flagsJson(s.flags);
  j["seeds"] = s.seeds;
  j["checkpoints"] = s.checkpoints;
  if (s.targetRelMse > 0) j["target_relmse"] = s.targetRelMse;
  j["scenes"] = json::array();
  for (const auto& sc : s.scenes) {
    json js{{"name", sc.name}, {"flags", flagsJson(sc.flags)}};
    if (!sc.path.empty()) js["path"] = sc.path;
    if (!sc.referenceFile.empty()) {
      js["reference"] = sc.referenceFile;
    } else {
      js["reference_spp"] = sc.referenceSpp;
    }
    j["scenes"].push_back(js);
  }
  j["configs"] = json::array();
  for (const auto& c : s.configs)
    j["configs"].push_back(json{{"name", c.name}, {"flags", flagsJson(c.flags)}});
  return j;
}

Sweep loadSweep(const fs::path& dir) {
  const fs::path file = dir / "sweep.json";
  std::string why;
  const auto text = readRegularFile(file, &why, 256u << 20);
  if (!text) {
    throw std::runtime_error("'" + dir.string() + "' holds no sweep (" + file.string() + ": " + why +
                             "); `workbench sweep SPEC ... --out DIR` makes one");
  }
  json root;
  try {
    root = json::parse(*text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(file.string() + ": line " + std::to_string(lineOf(*text, e.byte)) +
                             ": not valid JSON");
  }
  if (!root.contains("sweep") || !root.contains("tasks"))
    throw std::runtime_error(file.string() + ": not a sweep folder's sweep.json (no \"sweep\" or \"tasks\")");
  Sweep s;
  try {
    s = SpecReader(file.string() + " (\"sweep\")", "/").read(root["sweep"]);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  s.specFile = root.value("spec_file", "");
  std::vector<std::string> ids;
  for (const auto& t : s.tasks) ids.push_back(t.id);
  if (root["tasks"] != json(ids)) {
    throw std::runtime_error(file.string() +
                             ": its task list differs from the expansion of its sweep (written by another "
                             "version of the workbench?)");
  }
  return s;
}

void writeFileAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << text;
    if (!f.flush()) throw std::runtime_error("cannot write '" + tmp.string() + "'");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write '" + path.string() + "': " + ec.message());
  }
}

}  // namespace wb::app::sweep
