// The one CSV reader (base/csv.h): cells as RFC 4180 splits them, numbers only when the whole
// cell is one, errors at their file and line; and envelope.csv read back through it
// (sim/record/envelope_csv.h) with a located error for a bad cell or a short row.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/csv.h"
#include "sim/record/envelope_csv.h"

namespace metrosync {
namespace {

using Cells = std::vector<std::string>;

TEST(Csv, CellsAreSplitAsRfc4180Says) {
  EXPECT_EQ(csvCells("a,b,c"), (Cells{"a", "b", "c"}));
  EXPECT_EQ(csvCells(""), (Cells{""}));
  EXPECT_EQ(csvCells("a,"), (Cells{"a", ""}));  // a trailing comma: one more, empty cell
  EXPECT_EQ(csvCells(",,"), (Cells{"", "", ""}));
  EXPECT_EQ(csvCells("\"b,\"\"c\"\"\",d"), (Cells{"b,\"c\"", "d"}));  // quoted comma and quotes
  EXPECT_EQ(csvCells("x\"y,z"), (Cells{"x\"y", "z"}));  // a quote inside a cell is a character
  EXPECT_EQ(csvCells("1,2\r"), (Cells{"1", "2"}));      // a Windows line end
  EXPECT_THROW(csvCells("a,\"b"), std::invalid_argument);
}

TEST(Csv, ANumberIsTheWholeCell) {
  EXPECT_EQ(csvNumber("1.5"), 1.5);
  EXPECT_EQ(csvNumber("-2e-3"), -2e-3);
  EXPECT_TRUE(std::isnan(*csvNumber("nan")));
  EXPECT_TRUE(std::isinf(*csvNumber("-inf")));
  EXPECT_FALSE(csvNumber(""));
  EXPECT_FALSE(csvNumber("1.5x"));  // std::stod would have read 1.5
  EXPECT_FALSE(csvNumber("abc"));
  EXPECT_FALSE(csvNumber("1 "));
}

TEST(Csv, LinesKeepTheirNumbersAndErrorsSayWhere) {
  std::istringstream in("h1,h2\n\n1,2\r\n3,\"4\n");
  CsvLines lines(in, "data.csv");
  Cells c;
  ASSERT_TRUE(lines.next(c));
  EXPECT_EQ(lines.line(), 1);
  ASSERT_TRUE(lines.next(c));  // the empty line 2 skipped
  EXPECT_EQ(lines.line(), 3);
  EXPECT_EQ(c, (Cells{"1", "2"}));
  EXPECT_EQ(lines.text(), "1,2");
  try {
    lines.next(c);
    FAIL() << "no error";
  } catch (const CsvError& e) {
    EXPECT_STREQ(e.what(), "data.csv:4: unterminated quote");
    EXPECT_EQ(e.line, 4);
  }
}

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path =
      ::testing::TempDir() + "/metrosync_csv_" + name + "_" + std::to_string(::getpid());
  std::ofstream(path) << text;
  return path;
}

TEST(Csv, AnEnvelopeFileReadsBackWithItsColumns) {
  const std::string path = writeFile("env", "tau,A_1,A_2,psi_2,r\r\n0.5,1.25,2.5,3,0.75\r\n");
  const std::vector<EnvelopeRow> rows = readEnvelopeCsv(path);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].tau, 0.5);
  EXPECT_EQ(rows[0].A, (std::vector<double>{1.25, 2.5}));
  EXPECT_EQ(rows[0].psi, (std::vector<double>{3}));
  EXPECT_EQ(rows[0].r, 0.75);
  std::filesystem::remove(path);
}

TEST(Csv, AnEnvelopeFilesBadCellIsNamedWithItsLine) {
  for (const auto& [body, says] : std::vector<std::pair<std::string, std::string>>{
           {"0.1,1,1,0\n0.2,1,1.5x,0\n", ":3: bad number '1.5x'"},  // stod took 1.5 before
           {"0.1,1,1,0\n0.2,1,,0\n", ":3: bad number ''"},
           {"0.1,1,1\n", ":2: wrong number of columns (3, the header has 4)"}}) {
    const std::string path = writeFile("bad", "tau,A_1,A_2,psi_2\n" + body);
    try {
      readEnvelopeCsv(path);
      ADD_FAILURE() << "no error for " << body;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path + says), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace metrosync
