// One class per name: no two classes or structs of the same qualified name are defined with
// external linkage in the libraries and tools (a program holding both breaks the one-definition
// rule: their implicit members -- a destructor, say -- share a symbol with different bodies, and
// the linker keeps one). Found once: the validation's and tools/report's `metrosync::ProgressLog`
// (the first is ValidationLog now). A definition is a line at a namespace's top level that
// starts `class NAME` or `struct NAME` and is not a declaration alone; anonymous namespaces
// (internal linkage) do not count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kScanned = {"base", "contact", "models", "sim", "yaml", "tools"};

// Qualified name -> the places that define it, in one file's text (`file` names the places).
void collect(const std::string& text, const std::string& file,
             std::map<std::string, std::vector<std::string>>& defs) {
  static const std::regex open_named(R"(^namespace ([\w:]+) \{)");
  static const std::regex open_anon(R"(^namespace \{)");
  static const std::regex close(R"(^\}  // namespace)");
  static const std::regex def(R"(^(?:class|struct) (\w+)(?: final)?(?: :[^;]*| \{.*|)$)");
  std::vector<std::string> scope;  // "" for an anonymous namespace
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    std::smatch m;
    if (std::regex_search(line, m, open_named)) {
      scope.push_back(m[1]);
    } else if (std::regex_search(line, open_anon)) {
      scope.push_back("");
    } else if (std::regex_search(line, close)) {
      if (!scope.empty()) scope.pop_back();
    } else if (std::regex_match(line, m, def)) {
      std::string name;
      bool internal = false;
      for (const std::string& s : scope) {
        internal |= s.empty();
        name += s + "::";
      }
      if (!internal) defs[name + m[1].str()].push_back(file + ":" + std::to_string(n));
    }
  }
}

std::map<std::string, std::vector<std::string>> definitionsUnder(const fs::path& root) {
  std::map<std::string, std::vector<std::string>> defs;
  for (const std::string& top : kScanned)
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = e.path().extension().string();
      if (!e.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
      std::ifstream in(e.path());
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      collect(text, fs::relative(e.path(), root).string(), defs);
    }
  return defs;
}

TEST(OneClassPerName, NoTwoDefinitionsOfOneQualifiedName) {
  const auto defs = definitionsUnder(METROSYNC_SOURCE_DIR);
  ASSERT_GT(defs.size(), 100u) << "the scan finds too few classes: it is blind";
  ASSERT_EQ(defs.count("metrosync::ValidationLog"), 1u);
  std::string twice;
  for (const auto& [name, places] : defs)
    if (places.size() > 1) {
      twice += "  " + name + ":";
      for (const std::string& p : places) twice += " " + p;
      twice += "\n";
    }
  EXPECT_TRUE(twice.empty()) << "classes defined twice:\n" << twice;
}

// The checker on texts whose answer is known: a clash across files, none in anonymous namespaces
// or across namespaces, declarations alone ignored.
TEST(OneClassPerName, CheckerFindsAClashAndNothingElse) {
  std::map<std::string, std::vector<std::string>> defs;
  collect("namespace a {\n\nclass Log {\n};\n\nstruct Fwd;\n\n}  // namespace a\n", "one.h", defs);
  collect(
      "namespace a {\nnamespace {\nclass Helper {};\n}  // namespace\n\nclass Log final : public "
      "B {\n};\n}  // namespace a\n",
      "two.h", defs);
  collect(
      "namespace a::b {\nclass Log {\n};\n}  // namespace a::b\nnamespace {\nclass Helper "
      "{};\n}  // namespace\n",
      "three.h", defs);
  ASSERT_EQ(defs["a::Log"].size(), 2u);
  EXPECT_EQ(defs["a::Log"][0], "one.h:3");
  EXPECT_EQ(defs["a::Log"][1], "two.h:6");
  EXPECT_EQ(defs["a::b::Log"].size(), 1u);
  EXPECT_EQ(defs.count("a::Fwd"), 0u);
  EXPECT_EQ(defs.count("a::Helper"), 0u);
  EXPECT_EQ(defs.count("Helper"), 0u);
}

}  // namespace
