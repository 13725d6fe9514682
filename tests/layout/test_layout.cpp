// The layout's one rule (CMakeLists.txt, COMMON): every `#include "..."` of the libraries and
// tools points downwards in
//   base < contact < contact/simbody < models < models/simbody, sim/parallel < sim/ode, sim/record
//     < sim/events < sim/engines/{direct,simbody,slow_flow} < sim/engines < sim/analysis < yaml
//     < tools/report < tools/cli < tools
// or stays in its own folder. Folders of one level (sim/ode and sim/record, the three engines)
// do not include each other; tools/bench (a benchmark nothing links) may include anything;
// tests/ are not scanned. A folder the order does not name is itself a failure: a new library
// must be placed in the order here and in CMakeLists.txt.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// The level of each library folder; kAnything for the folders that may include anything.
constexpr int kAnything = 1000;
const std::map<std::string, int>& levels() {
  static const std::map<std::string, int> m = {
      {"base", -1},  // the constants and number text every library may use
      {"contact", 0},
      {"contact/simbody", 1},
      {"models", 2},
      {"models/simbody", 3},
      {"sim/parallel", 3},
      {"sim/ode", 4},
      {"sim/record", 4},
      {"sim/events", 5},
      {"sim/engines/direct", 6},
      {"sim/engines/simbody", 6},
      {"sim/engines/slow_flow", 6},
      {"sim/engines", 7},
      {"sim/analysis", 8},
      {"yaml", 9},
      {"tools/report", 10},
      {"tools/cli", 11},
      {"tools", 12},
      {"tools/bench", kAnything},
  };
  return m;
}

// The scanned top-level folders (the libraries and tools; not tests/, not build/).
const std::vector<std::string> kScanned = {"base", "contact", "models", "sim", "yaml", "tools"};

std::optional<int> levelOf(const std::string& folder) {
  // a folder below a library folder that the order does not name sits with it (e.g.
  // tools/bench/cmake)
  for (std::string f = folder; !f.empty();) {
    const auto it = levels().find(f);
    if (it != levels().end()) return it->second;
    const size_t slash = f.rfind('/');
    if (slash == std::string::npos) break;
    f = f.substr(0, slash);
    if (f == "sim") break;  // sim/ itself is no library: sim/foo must be named
  }
  return std::nullopt;
}

std::string folderOf(const std::string& rel_path) {
  const size_t slash = rel_path.rfind('/');
  return slash == std::string::npos ? "" : rel_path.substr(0, slash);
}

std::string libraryOf(const std::string& folder) {
  for (std::string f = folder; !f.empty(); f = folderOf(f))
    if (levels().count(f)) return f;
  return folder;
}

// Every violation under `root`, one line each: "FILE:LINE: includes TARGET (why)".
std::vector<std::string> layoutViolations(const fs::path& root) {
  static const std::regex include_re(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::vector<std::string> out;
  for (const auto& top : kScanned) {
    if (!fs::is_directory(root / top)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string rel = fs::relative(e.path(), root).generic_string();
      const std::string from = libraryOf(folderOf(rel));
      const std::optional<int> from_level = levelOf(folderOf(rel));
      std::ifstream in(e.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n) {
        std::smatch m;
        if (!std::regex_search(line, m, include_re)) continue;
        const std::string target = m[1];
        const std::string where = rel + ":" + std::to_string(n) + ": includes " + target;
        if (!fs::exists(root / target)) {
          out.push_back(where + " (not a path from the repository root)");
          continue;
        }
        const std::string to = libraryOf(folderOf(target));
        const std::optional<int> to_level = levelOf(folderOf(target));
        if (!from_level) {
          out.push_back(where + " (" + folderOf(rel) + " is not in the layout's order)");
        } else if (!to_level) {
          out.push_back(where + " (" + folderOf(target) + " is not in the layout's order)");
        } else if (from == to || *from_level == kAnything) {
          continue;
        } else if (*to_level > *from_level) {
          out.push_back(where + " (upwards: " + from + " -> " + to + ")");
        } else if (*to_level == *from_level) {
          out.push_back(where + " (sideways: " + from + " and " + to + " are one level)");
        }
      }
    }
  }
  return out;
}

// A file's unit: its path without the extension (x.h and x.cpp are one unit).
std::string unitOf(const std::string& rel_path) {
  return fs::path(rel_path).replace_extension().generic_string();
}

// The include cycles between units under `root`: each a sorted list of the units of one strongly
// connected component of "a file of unit A includes a header of unit B" (Tarjan).
std::vector<std::vector<std::string>> includeCycles(const fs::path& root) {
  static const std::regex include_re(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::map<std::string, std::vector<std::string>> edges;
  for (const auto& top : kScanned) {
    if (!fs::is_directory(root / top)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      const std::string unit = unitOf(fs::relative(e.path(), root).generic_string());
      std::ifstream in(e.path());
      std::string line;
      while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, include_re) || !fs::exists(root / m[1].str())) continue;
        const std::string to = unitOf(m[1]);
        if (to != unit) edges[unit].push_back(to);
      }
    }
  }
  std::map<std::string, int> index, low;
  std::vector<std::string> stack;
  std::map<std::string, bool> on_stack;
  std::vector<std::vector<std::string>> cycles;
  int next = 0;
  std::function<void(const std::string&)> visit = [&](const std::string& v) {
    index[v] = low[v] = next++;
    stack.push_back(v);
    on_stack[v] = true;
    for (const std::string& w : edges[v]) {
      if (!index.count(w)) {
        visit(w);
        low[v] = std::min(low[v], low[w]);
      } else if (on_stack[w]) {
        low[v] = std::min(low[v], index[w]);
      }
    }
    if (low[v] != index[v]) return;
    std::vector<std::string> component;
    for (std::string w; w != v;) {
      w = stack.back();
      stack.pop_back();
      on_stack[w] = false;
      component.push_back(w);
    }
    if (component.size() > 1) {
      std::sort(component.begin(), component.end());
      cycles.push_back(component);
    }
  };
  std::vector<std::string> units;
  for (const auto& [u, to] : edges) units.push_back(u);
  for (const std::string& u : units)
    if (!index.count(u)) visit(u);
  return cycles;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += "  " + x + "\n";
  return s;
}

TEST(Layout, EveryIncludePointsDownwards) {
  const std::vector<std::string> v = layoutViolations(METROSYNC_SOURCE_DIR);
  EXPECT_TRUE(v.empty()) << v.size() << " includes against the layout:\n" << joined(v);
}

// The validation's files (sim/analysis/validation/: catalogue, runs, measures, checks, plan,
// parts, parts 6 and 7) include each other one way only (issue 24: validation.h and
// validation_bifurcations included each other).
TEST(Layout, NoIncludeCycleThroughTheValidation) {
  for (const auto& cycle : includeCycles(METROSYNC_SOURCE_DIR))
    for (const std::string& unit : cycle)
      EXPECT_EQ(unit.rfind("sim/analysis/validation", 0), std::string::npos)
          << "an include cycle through " << unit << ":\n"
          << joined(cycle);
}

// No include cycle anywhere (issue 24: continue <-> continue_full, commands <-> engines <->
// network_run, ceres_plugin <-> least_squares, rig_build <-> rig_loader <-> rig_source, the
// sweep's files, the bench's run and peers, the driven Coulomb harness), except the continuation's
// walk: the arclength walk meets a border and follows it as border states, which walk again
// (walkFrom <-> border_states, borders, family, smooth events, test functions), one recursion
// spread over its files.
TEST(Layout, NoIncludeCycleOutsideTheContinuationsWalk) {
  for (const auto& cycle : includeCycles(METROSYNC_SOURCE_DIR))
    for (const std::string& unit : cycle)
      EXPECT_EQ(unit.rfind("sim/analysis/continuation/", 0), 0u)
          << "an include cycle through " << unit << ":\n"
          << joined(cycle);
}

// The files of an engine's folder that define a window's resolution (a run class: `resolveWindow`
// with a body). One per engine (issue 24: the direct engine had two run classes, one per model,
// DirectRun<N> for a single rig and NetworkRun for a network; now one run over a model policy).
std::map<std::string, std::vector<std::string>> runClassFiles(const fs::path& root) {
  static const std::regex def(R"(\bresolveWindow\([^;{)]*\)[^;{]*\{)");
  std::map<std::string, std::vector<std::string>> files;
  for (const auto& e : fs::recursive_directory_iterator(root / "sim" / "engines")) {
    if (!e.is_regular_file()) continue;
    const std::string ext = e.path().extension().string();
    if (ext != ".h" && ext != ".cpp") continue;
    std::ifstream in(e.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!std::regex_search(text, def)) continue;
    const std::string rel = fs::relative(e.path(), root).generic_string();
    files[folderOf(rel)].push_back(rel);
  }
  return files;
}

TEST(Layout, OneRunClassPerEngine) {
  const auto files = runClassFiles(METROSYNC_SOURCE_DIR);
  ASSERT_TRUE(files.count("sim/engines/direct")) << "the direct engine's run was not found";
  ASSERT_TRUE(files.count("sim/engines/simbody")) << "the Simbody engine's run was not found";
  for (const auto& [folder, list] : files)
    EXPECT_EQ(list.size(), 1u) << folder << " has " << list.size() << " run classes:\n"
                               << joined(list);
}

TEST(Layout, IncludeCycleFinderFindsACycle) {
  const fs::path root =
      fs::path(::testing::TempDir()) / ("metrosync_cycles_" + std::to_string(::getpid()));
  fs::remove_all(root);
  auto file = [&](const std::string& rel, const std::string& text) {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel) << text;
  };
  file("sim/analysis/a.h", "#include \"sim/analysis/b.h\"\n");
  file("sim/analysis/b.h", "");
  file("sim/analysis/b.cpp", "#include \"sim/analysis/a.h\"\n");  // a.h -> b.h, b.cpp -> a.h
  file("sim/analysis/c.cpp", "#include \"sim/analysis/a.h\"\n");  // no cycle through c
  const auto cycles = includeCycles(root);
  fs::remove_all(root);
  ASSERT_EQ(cycles.size(), 1u);
  EXPECT_EQ(cycles[0], (std::vector<std::string>{"sim/analysis/a", "sim/analysis/b"}));
}

// The checker itself, on a small tree with one include of each kind: it must be able to fail.
class LayoutChecker : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("metrosync_layout_" + std::to_string(::getpid()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  void file(const std::string& rel, const std::string& text = "") {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << text;
  }
  std::vector<std::string> violations() { return layoutViolations(root_); }
  fs::path root_;
};

TEST_F(LayoutChecker, AcceptsDownwardsAndOwnFolder) {
  file("contact/coulomb.h");
  file("contact/simbody/element.h", "#include \"contact/coulomb.h\"\n");
  file("models/rig.h", "#include \"contact/coulomb.h\"\n#include \"models/rig.h\"\n");
  file("sim/engines/engine.h", "#include \"sim/engines/direct/d.h\"\n");
  file("sim/engines/direct/d.h", "  #  include \"models/rig.h\"  // spaced\n");
  file("tools/cli/c.cpp", "#include \"sim/engines/engine.h\"\n#include <vector>\n");
  file("tools/bench/b.cpp", "#include \"tools/cli/c.cpp\"\n");  // bench may include anything
  EXPECT_TRUE(violations().empty()) << joined(violations());
}

TEST_F(LayoutChecker, FlagsUpwardsSidewaysUnknownAndUnresolved) {
  file("contact/coulomb.h", "#include \"models/rig.h\"\n");  // the old FrictionLaw include
  file("models/rig.h");
  file("models/slow.h", "#include \"sim/engines/slow_flow/s.h\"\n");
  file("sim/engines/slow_flow/s.h");
  file("sim/engines/direct/d.h", "#include \"sim/engines/slow_flow/s.h\"\n");
  file("sim/newthing/n.h", "#include \"models/rig.h\"\n");
  file("yaml/y.cpp", "#include \"rig.h\"\n");
  const std::vector<std::string> v = violations();
  ASSERT_EQ(v.size(), 5u) << joined(v);
  const std::string all = joined(v);
  for (const char* expect :
       {"contact/coulomb.h:1: includes models/rig.h (upwards: contact -> models)",
        "models/slow.h:1: includes sim/engines/slow_flow/s.h (upwards",
        "sim/engines/direct/d.h:1: includes sim/engines/slow_flow/s.h (sideways",
        "sim/newthing is not in the layout's order", "yaml/y.cpp:1: includes rig.h (not a path"})
    EXPECT_NE(all.find(expect), std::string::npos) << expect << "\n" << all;
}

}  // namespace
