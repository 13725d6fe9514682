// `metrosync figures` end to end: every file figures.md and figures.json list exists and is not
// empty, and each f4.x curve's numbers (final state and regime of the slow flow) are the ones the
// validation report computes for that scenario: validation's part 2 is run here, through
// runValidation and validationJson (the report's summary.json), not copied from a file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "sim/analysis/validation/validation.h"
#include "tests/common/run_metrosync.h"
#include "tools/cli/validate.h"
#include "tools/report/validation_report.h"

namespace {

namespace fs = std::filesystem;
namespace ts = metrosync::testing_support;
using nlohmann::json;

std::string rigsDir() {
  return std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs";
}

// The validation report's summary.json with only part 2 (the paper's scenarios, slow flow):
// the other parts' lists emptied, so no full-model run is needed.
json validationScenarios() {
  metrosync::ValidationPlan plan = metrosync::defaultValidationPlan(true);
  plan.beta_s.clear();
  plan.convergence_scenarios.clear();
  plan.regime_scenarios.clear();
  plan.sweep_mu.clear();
  metrosync::ValidationEngines engines;  // part 2 runs the slow flow only
  const metrosync::ValidationResults res =
      metrosync::runValidation(plan, metrosync::cli::loadScenarios(rigsDir()), engines);
  return metrosync::validationJson(res, {})["scenarios"];
}

// Files linked from figures.md: "(name.png)", "(name.svg)".
std::set<std::string> linkedFiles(const std::string& md) {
  std::set<std::string> files;
  const std::regex link(R"(\]\(([A-Za-z0-9_.\-]+\.(png|svg))\))");
  for (std::sregex_iterator it(md.begin(), md.end(), link), end; it != end; ++it)
    files.insert((*it)[1]);
  return files;
}

TEST(Figures, WritesEveryListedFileWithTheValidationReportsNumbers) {
  const std::string out = ts::scratchDir("figures", "slow");
  const ts::CommandResult r =
      ts::runMetrosync("figures --model slow --quick -q --rigs " + ts::shellQuote(rigsDir()) +
                       " --out " + ts::shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(ts::slurp(out + "/figures.json"));

  // every figure of section 4 and the map, each with its command alone and both formats
  std::set<std::string> listed;
  std::set<std::string> ids;
  for (const char* part : {"figures", "maps"})
    for (const auto& f : j.at(part)) {
      ids.insert(f.at("id").get<std::string>());
      EXPECT_NE(f.at("command").get<std::string>().find("--only " + f.at("id").get<std::string>()),
                std::string::npos);
      for (const auto& name : f.at("files")) listed.insert(name.get<std::string>());
    }
  EXPECT_EQ(ids, (std::set<std::string>{"f4.1", "f4.2", "f4.3", "f4.4", "exp1"}));
  EXPECT_EQ(listed.size(), 10u);
  const std::string md = ts::slurp(out + "/figures.md");
  EXPECT_EQ(linkedFiles(md), listed);
  for (const auto& name : listed) {
    EXPECT_TRUE(fs::is_regular_file(out + "/" + name)) << name;
    EXPECT_GT(fs::file_size(out + "/" + name), 1000u) << name;
    EXPECT_NE(md.find("metrosync figures --only " + name.substr(0, name.rfind('.'))),
              std::string::npos)
        << name;
  }

  // the curves' numbers against the validation report's, scenario by scenario
  const json scenarios = validationScenarios();
  int compared = 0;
  for (const auto& f : j.at("figures"))
    for (const auto& run : f.at("runs")) {
      const std::string name = run.at("scenario");
      const auto it = std::find_if(scenarios.begin(), scenarios.end(),
                                   [&](const json& s) { return s.at("name") == name; });
      ASSERT_NE(it, scenarios.end()) << name;
      const json& v = it->at("slow");
      const json& mine = run.at("slow");
      EXPECT_EQ(mine.at("regime"), v.at("regime")) << name;
      EXPECT_EQ(mine.at("final"), v.at("final")) << name;  // tau, A, psi to the last bit
      EXPECT_EQ(mine.at("epsilon"), v.at("epsilon")) << name;
      EXPECT_EQ(mine.at("tau_end"), v.at("tau_end")) << name;
      ++compared;
    }
  EXPECT_EQ(compared, 8);  // the paper's eight simulations
  EXPECT_EQ(static_cast<int>(scenarios.size()), 8);

  // the map: one regime per grid point
  const json& map = j.at("maps").at(0);
  long points = 0;
  for (const auto& [regime, count] : map.at("regimes").items()) points += count.get<long>();
  EXPECT_EQ(points, map.at("grid").at("points").get<long>());
  EXPECT_TRUE(map.at("complete").get<bool>());
  fs::remove_all(out);
}

TEST(Figures, OnlyMakesThatFigureAndABadIdWritesNothing) {
  const std::string out = ts::scratchDir("figures", "only");
  ASSERT_EQ(ts::runMetrosync("figures --only f4.2 -q --rigs " + ts::shellQuote(rigsDir()) +
                             " --out " + ts::shellQuote(out))
                .code,
            0);
  EXPECT_TRUE(fs::exists(out + "/f4.2.svg"));
  // the threshold's legend is θ with a subscript c, not the text "θ_c" (the key is noenhanced
  // for the runs' own labels)
  const std::string svg = ts::slurp(out + "/f4.2.svg");
  EXPECT_EQ(svg.find("θ_c"), std::string::npos);
  EXPECT_TRUE(std::regex_search(svg, std::regex("θ</tspan><tspan[^>]*>c</tspan>"))) << svg;
  EXPECT_FALSE(fs::exists(out + "/f4.3.png"));
  EXPECT_FALSE(fs::exists(out + "/exp1.png"));
  const std::string bad = ts::scratchDir("figures", "bad");
  EXPECT_EQ(ts::runMetrosync("figures --only f9.9 --out " + ts::shellQuote(bad)).code, 2);
  EXPECT_FALSE(fs::exists(bad));
  fs::remove_all(out);
}

}  // namespace
