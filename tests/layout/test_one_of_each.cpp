// One of each (issue 38): no code outside contact/ names a friction law's kind (the engines and
// analyses ask the law, contact/platform_friction.h and contact/slow_response.h, never which law
// it is), and the full model has one equation class and one direct model -- today two of each,
// the listed exceptions below, which issue 38's "One model" removes.
//
// A law's kind is named by its registry accessor (contact/law_registry.h: X(coulombLaw) ...),
// by comparing a law with one built by name (`== FrictionLaw::coulomb(...)`), by comparing a
// name with one of the laws' names ("coulomb", ...: each law file's name()), or by looking a law
// up by a literal name (findLaw("coulomb", ...)). Building a law by name (FrictionLaw::coulomb(mu)
// for the paper's validation, the bench's scenes) is not a switch on it and is allowed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// The scanned top-level folders (the libraries and tools; not tests/, not build/).
const std::vector<std::string> kScanned = {"base", "contact", "models", "sim", "yaml", "tools"};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool isSource(const fs::directory_entry& e) {
  const std::string ext = e.path().extension().string();
  return e.is_regular_file() && (ext == ".h" || ext == ".cpp");
}

std::vector<std::string> matches(const std::string& text, const std::regex& re, int group) {
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[group]);
  return out;
}

// The laws as code names them: each registry accessor, each rig-file name.
struct LawNames {
  std::vector<std::string> accessors, names;
};

LawNames lawNamesIn(const fs::path& root) {
  LawNames n;
  static const std::regex accessor(R"(\bX\((\w+)\))");
  n.accessors = matches(slurp(root / "contact" / "law_registry.h"), accessor, 1);
  static const std::regex name(R"(\bname\(\)\s*const\s*override\s*\{\s*return\s*"(\w+)\")");
  for (const auto& e : fs::directory_iterator(root / "contact"))
    if (isSource(e))
      for (const std::string& s : matches(slurp(e.path()), name, 1)) n.names.push_back(s);
  return n;
}

std::string alternatives(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : "|") + w;
  return "(" + s + ")";
}

// Every line outside contact/ that names a law's kind: "FILE:LINE: TEXT".
std::vector<std::string> lawKindMentions(const fs::path& root) {
  const LawNames laws = lawNamesIn(root);
  std::vector<std::regex> rules;
  if (!laws.accessors.empty()) rules.emplace_back("\\b" + alternatives(laws.accessors) + "\\s*\\(");
  rules.emplace_back(R"([!=]=\s*FrictionLaw::\w+\(|FrictionLaw::\w+\([^()]*\)\s*[!=]=)");
  rules.emplace_back(R"(\bfindLaw\(\s*")");
  // a closed list of laws switched on: an enum of the law types (main before issue 38 had
  // PlatformFriction::Kind {SetValued, Viscous, None, Fixed}, SlowResponse::Kind {.., Coulomb})
  rules.emplace_back(R"(\b(PlatformFriction|SlowResponse|FrictionLaw|LawKind)::Kind\b)");
  if (!laws.names.empty()) {
    std::vector<std::string> capitalised;
    for (std::string n : laws.names) {
      n[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(n[0])));
      capitalised.push_back(n);
    }
    rules.emplace_back("\\bKind::" + alternatives(capitalised) + "\\b");
  }
  if (!laws.names.empty()) {
    const std::string quoted = "(std::string\\()?\"" + alternatives(laws.names) + "\"";
    rules.emplace_back("[!=]=\\s*" + quoted + "|" + quoted + "\\)?\\s*[!=]=");
  }
  std::vector<std::string> out;
  for (const std::string& top : kScanned) {
    if (top == "contact" || !fs::is_directory(root / top)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      if (!isSource(e)) continue;
      std::ifstream in(e.path());
      std::string line;
      for (int k = 1; std::getline(in, line); ++k)
        for (const std::regex& r : rules)
          if (std::regex_search(line, r)) {
            out.push_back(fs::relative(e.path(), root).generic_string() + ":" + std::to_string(k) +
                          ": " + line);
            break;
          }
    }
  }
  return out;
}

// The classes and structs defined in `text` whose body matches `member`.
std::set<std::string> classesWith(const std::string& text, const std::regex& member) {
  static const std::regex head(R"(\b(class|struct)\s+(\w+)[^;{()]*\{)");
  std::set<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), head); it != std::sregex_iterator();
       ++it) {
    const size_t open = it->position() + it->length() - 1;
    size_t close = open;
    for (int depth = 0; close < text.size(); ++close) {
      if (text[close] == '{') ++depth;
      if (text[close] == '}' && --depth == 0) break;
    }
    if (std::regex_search(text.substr(open, close - open), member)) out.insert((*it)[2]);
  }
  return out;
}

std::set<std::string> classesUnder(const fs::path& dir, const std::regex& member) {
  std::set<std::string> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir))
    if (isSource(e))
      for (const std::string& c : classesWith(slurp(e.path()), member)) out.insert(c);
  return out;
}

// An equation class of the full model: a class in models/ with a member that takes the state
// `const double* y` and writes its derivative `double* dy` (the slow flow's complex amplitudes
// and the Simbody assembly in models/simbody are other models).
std::set<std::string> equationClasses(const fs::path& root) {
  static const std::regex rhs(R"(\(\s*const\s+double\s*\*\s*y\b[^)]*\bdouble\s*\*\s*dy\b)");
  return classesUnder(root / "models", rhs);
}

// A direct model: a class in sim/engines/direct/ that a direct run starts: it declares
// `startState()` (a type before the name; the run's call m_.startState() is no declaration).
std::set<std::string> directModels(const fs::path& root) {
  static const std::regex start(R"([\w>&*]\s+startState\(\s*\))");
  return classesUnder(root / "sim" / "engines" / "direct", start);
}

// The listed exceptions: today's twins (issue 38, "One model": one equation class per platform
// arrow, one direct model). That work removes them; a list that no longer matches the tree fails.
const std::set<std::string> kEquationClassTwins = {};
const std::set<std::string> kDirectModelTwins = {};

// One class, or exactly the listed twins.
void expectOne(const std::set<std::string>& found, const std::set<std::string>& twins,
               const std::string& what) {
  std::string list;
  for (const std::string& c : found) list += "  " + c + "\n";
  ASSERT_FALSE(found.empty()) << "no " << what << " found: the checker is blind";
  if (found.size() == 1) {
    EXPECT_TRUE(twins.empty()) << "one " << what << " left (" << *found.begin()
                               << "): remove the listed exception";
    return;
  }
  EXPECT_EQ(found, twins) << found.size() << " " << what << "es:\n"
                          << list << "(only the listed exception may be two)";
}

TEST(OneOfEach, NoCodeOutsideContactNamesALawsKind) {
  const LawNames laws = lawNamesIn(METROSYNC_SOURCE_DIR);
  ASSERT_GE(laws.accessors.size(), 5u) << "the registry's laws were not found";
  ASSERT_GE(laws.names.size(), 5u) << "the laws' names were not found";
  const std::vector<std::string> v = lawKindMentions(METROSYNC_SOURCE_DIR);
  std::string all;
  for (const std::string& s : v) all += "  " + s + "\n";
  EXPECT_TRUE(v.empty()) << v.size() << " lines outside contact/ name a law's kind:\n" << all;
}

TEST(OneOfEach, OneEquationClass) {
  expectOne(equationClasses(METROSYNC_SOURCE_DIR), kEquationClassTwins, "equation class");
}

TEST(OneOfEach, OneDirectModel) {
  expectOne(directModels(METROSYNC_SOURCE_DIR), kDirectModelTwins, "direct model");
}

// A failed run's message is made in one place for every engine and every kind of rig
// (sim/record/failure_text.h, failureText; main had one function for a rig and one for a
// network): the message's literal once in the scanned folders (tools/bench's peers, independent
// programs on purpose, left out).
TEST(OneOfEach, OneFailureMessage) {
  const fs::path root = METROSYNC_SOURCE_DIR;
  const std::string literal = "\"simulation failed at t = \"";
  std::vector<std::string> where;
  for (const std::string& top : kScanned)
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      const std::string rel = fs::relative(e.path(), root).generic_string();
      if (!isSource(e) || rel.rfind("tools/bench/", 0) == 0) continue;
      const std::string text = slurp(e.path());
      for (size_t at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1))
        where.push_back(rel);
    }
  std::string all;
  for (const std::string& w : where) all += "  " + w + "\n";
  EXPECT_EQ(where, std::vector<std::string>{"sim/record/failure_text.h"}) << all;
}

// The checkers themselves, on a small tree: they must be able to fail.
class OneOfEachChecker : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("metrosync_one_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    file("contact/law_registry.h", "#define LAWS(X) \\\n  X(coulombLaw) \\\n  X(viscousLaw)\n");
    file("contact/coulomb.cpp",
         "const char* name() const override { return \"coulomb\"; }\nbool a = is(coulombLaw());\n");
    file("contact/viscous.cpp", "const char* name() const override { return \"viscous\"; }\n");
  }
  void TearDown() override { fs::remove_all(root_); }
  void file(const std::string& rel, const std::string& text) {
    fs::create_directories((root_ / rel).parent_path());
    std::ofstream(root_ / rel) << text;
  }
  fs::path root_;
};

TEST_F(OneOfEachChecker, FlagsEveryWayOfNamingALawsKindOutsideContact) {
  file("sim/a.cpp",
       "bool a = law.is(coulombLaw());\n"                      // 1: an accessor
       "bool b = law == FrictionLaw::viscous(0.1);\n"          // 2: a law built by name
       "bool c = law.name() == std::string(\"viscous\");\n"    // 3: a name
       "const LawKind* d = findLaw(\"coulomb\", {\"mu\"});\n"  // 4: a lookup by name
       "const FrictionLaw e = FrictionLaw::coulomb(0.1);\n"    // building one: allowed
       "bool f = law.setValued() && law.platform(1).constantSlipForce();\n"  // asking it: allowed
       "bool g = symmetry == \"none\";\n"                                    // not a law's name
       "bool h = f.kind == PlatformFriction::Kind::Viscous;\n"  // 8: an enum of the laws
       "case Kind::Coulomb: break;\n"                           // 9: one of its members
       "Notation n = Notation::Fixed;\n");                      // another enum: allowed
  const std::vector<std::string> v = lawKindMentions(root_);
  const std::vector<int> lines = {1, 2, 3, 4, 8, 9};
  ASSERT_EQ(v.size(), lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k)
    EXPECT_EQ(v[k].rfind("sim/a.cpp:" + std::to_string(lines[k]) + ":", 0), 0u) << v[k];
}

TEST_F(OneOfEachChecker, CountsEquationClassesAndDirectModels) {
  file("models/eq.h",
       "class Eq {\n public:\n  void rhs(const double* y, PlatformMode m, double* dy) const;\n"
       "  struct Inner { int n; };\n};\nstruct Helper { double f(const double* y); };\n");
  file("sim/engines/direct/model.h",
       "template <int N>\nclass Model final : public EventSystem {\n"
       "  std::vector<double> startState();\n};\n");
  file("sim/engines/direct/run.h", "class Run {\n  void go() { y = m_.startState(); }\n};\n");
  EXPECT_EQ(equationClasses(root_), (std::set<std::string>{"Eq"}));
  EXPECT_EQ(directModels(root_), (std::set<std::string>{"Model"}));
  // a second one appears
  file("models/eq2.cpp", "class Other {\n  void derivative(const double* y, double* dy);\n};\n");
  file("sim/engines/direct/other.h", "class OtherModel {\n  auto startState() const;\n};\n");
  EXPECT_EQ(equationClasses(root_), (std::set<std::string>{"Eq", "Other"}));
  EXPECT_EQ(directModels(root_), (std::set<std::string>{"Model", "OtherModel"}));
}

}  // namespace
