// Rows formatted on a writer thread (tools/report/deferred_rows.h): the file holds every row in
// order, as the run's thread would have written it, through many blocks and a full queue; a
// writer's error reaches the run's thread; nothing is left running when the rows are dropped.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "sim/record/atomic_file.h"
#include "tools/report/deferred_rows.h"

namespace metrosync {
namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "/metrosync_deferred_" + name + "_" + std::to_string(::getpid());
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// the same text, made on this thread: the reference the writer must reproduce
std::string expectedText(long rows) {
  std::string text;
  for (long k = 0; k < rows; ++k)
    text += std::to_string(k) + "," + std::to_string(2 * k) + "," + std::to_string(-k) + "\n";
  return text;
}

bool formatRow(const double* row, std::string& line) {
  for (int k = 0; k < 3; ++k) line += (k ? "," : "") + std::to_string(static_cast<long>(row[k]));
  return true;
}

TEST(DeferredRows, EveryRowInOrderThroughManyBlocksAndAFullQueue) {
  // 20 000 rows: ~78 blocks of 256, ten times the queue's bound, so the run's thread waits
  const long rows = 20000;
  const std::string path = tempPath("order");
  {
    AtomicFile file(path);
    DeferredRows text(file, 3, formatRow);
    for (long k = 0; k < rows; ++k) {
      const double row[3] = {static_cast<double>(k), 2.0 * k, -static_cast<double>(k)};
      text.add(row);
    }
    text.finish();
    file.commit();
  }
  EXPECT_EQ(slurp(path), expectedText(rows));
  std::filesystem::remove(path);
}

// Rows that come from a recording thread already are written by it (writeOnCallersThread): the
// same text, each full block in the file as soon as it is added, on the adding thread.
TEST(DeferredRows, OnTheCallersThreadTheSameTextBlockByBlock) {
  const long rows = 1000;  // three full blocks of 256 and a partial one
  const std::string path = tempPath("caller");
  {
    AtomicFile file(path);
    const std::thread::id caller = std::this_thread::get_id();
    bool elsewhere = false;
    long formatted = 0;
    DeferredRows text(file, 3, [&](const double* row, std::string& line) {
      elsewhere = elsewhere || std::this_thread::get_id() != caller;
      ++formatted;
      return formatRow(row, line);
    });
    text.writeOnCallersThread();
    for (long k = 0; k < rows; ++k) {
      const double row[3] = {static_cast<double>(k), 2.0 * k, -static_cast<double>(k)};
      text.add(row);
      if (k == 254) EXPECT_EQ(formatted, 0);
      if (k == 255) EXPECT_EQ(formatted, 256);  // the first block, made by that add
    }
    EXPECT_EQ(formatted, 768);
    text.finish();
    EXPECT_EQ(formatted, rows);
    file.commit();
    EXPECT_FALSE(elsewhere);
  }
  EXPECT_EQ(slurp(path), expectedText(rows));
  std::filesystem::remove(path);
}

TEST(DeferredRows, OnTheCallersThreadAnErrorComesFromAdd) {
  const std::string path = tempPath("caller_error");
  AtomicFile file(path);
  DeferredRows text(file, 1, [](const double* row, std::string& line) {
    if (row[0] == 300) throw std::runtime_error("cannot write row 300");
    line += std::to_string(row[0]);
    return true;
  });
  text.writeOnCallersThread();
  int k = 0;
  try {
    for (; k < 1000; ++k) {
      const double v = k;
      text.add(&v);
    }
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write row 300");
  }
  EXPECT_EQ(k, 511);  // the add of row 511, which filled the block of rows 256..511
  file.discard();
}

TEST(DeferredRows, AFewRowsAreWrittenByFinish) {
  const std::string path = tempPath("few");
  {
    AtomicFile file(path);
    DeferredRows text(file, 3, formatRow);
    for (long k = 0; k < 5; ++k) {
      const double row[3] = {static_cast<double>(k), 2.0 * k, -static_cast<double>(k)};
      text.add(row);
    }
    text.finish();
    text.finish();  // twice: nothing more
    file.commit();
  }
  EXPECT_EQ(slurp(path), expectedText(5));
  std::filesystem::remove(path);
}

TEST(DeferredRows, TheWritersErrorReachesTheRunsThread) {
  const std::string path = tempPath("error");
  AtomicFile file(path);
  DeferredRows text(file, 1, [](const double* row, std::string& line) {
    if (row[0] == 300) throw std::runtime_error("cannot write row 300");
    line += std::to_string(row[0]);
    return true;
  });
  bool thrown = false;
  try {
    for (int k = 0; k < 100000; ++k) {
      const double v = k;
      text.add(&v);
    }
    text.finish();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "cannot write row 300");
  }
  EXPECT_TRUE(thrown);
  file.discard();
}

TEST(DeferredRows, DroppedUnfinishedStopsItsWriter) {
  const std::string path = tempPath("dropped");
  AtomicFile file(path);
  std::atomic<long> formatted{0};
  {
    DeferredRows text(file, 1, [&](const double*, std::string& line) {
      ++formatted;
      line += "x";
      return true;
    });
    for (int k = 0; k < 5000; ++k) {
      const double v = k;
      text.add(&v);
    }
  }  // no finish(): the writer stops, whatever it had not written is dropped
  const long at_stop = formatted.load();
  EXPECT_LE(at_stop, 5000);
  EXPECT_EQ(formatted.load(), at_stop);  // nothing runs on after the destructor
  file.discard();
}

}  // namespace
}  // namespace metrosync
