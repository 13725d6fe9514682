// orderedTasks (sim/parallel/ordered_tasks.h): the loop "for k: if (!skip(k)) { compute(k);
// commit(k); }" with compute run ahead on threads must give the sequential loop's commits, in
// its order, whatever the threads and however long each compute takes; errors surface at their
// turn.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "sim/parallel/ordered_tasks.h"

namespace metrosync {
namespace {

// A loop whose skips depend on what was committed before: k is skipped when a committed j < k
// "covers" it (k % j == 0 for j >= 2), so the set of committed k is the primes below count, and
// 0 and 1 are committed too. compute(k) records k's square, slower for small k.
std::vector<long> run(long count, int jobs) {
  std::vector<long> committed, value(count, -1);
  std::vector<bool> covered(count, false);
  orderedTasks(
      count, jobs, [&](long k) { return covered[k]; },
      [&](long k) {
        std::this_thread::sleep_for(std::chrono::microseconds((count - k) % 7 * 50));
        value[k] = k * k;
      },
      [&](long k) {
        EXPECT_EQ(value[k], k * k);
        committed.push_back(k);
        if (k >= 2)
          for (long m = 2 * k; m < count; m += k) covered[m] = true;
      });
  return committed;
}

TEST(OrderedTasks, CommitsTheSequentialLoopsStepsInOrder) {
  const std::vector<long> sequential = run(200, 1);
  std::vector<long> primes = {0, 1};
  for (long k = 2; k < 200; ++k) {
    bool prime = true;
    for (long j = 2; j * j <= k; ++j) prime = prime && k % j != 0;
    if (prime) primes.push_back(k);
  }
  EXPECT_EQ(sequential, primes);
  for (int jobs : {2, 3, 8}) EXPECT_EQ(run(200, jobs), primes) << jobs;
}

TEST(OrderedTasks, AComputeErrorIsRethrownAtItsTurnOnly) {
  for (int jobs : {1, 3}) {
    std::vector<long> committed;
    const auto compute = [](long k) {
      if (k == 5 || k == 9) throw std::runtime_error("step " + std::to_string(k));
    };
    // 9 is skipped: its error never surfaces; 5's does, after 0..4 are committed
    try {
      orderedTasks(
          12, jobs, [](long k) { return k == 9; }, compute,
          [&](long k) { committed.push_back(k); });
      ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "step 5");
    }
    EXPECT_EQ(committed, (std::vector<long>{0, 1, 2, 3, 4})) << jobs;
  }
}

TEST(OrderedTasks, ACommitErrorStopsTheLoop) {
  std::vector<long> committed;
  EXPECT_THROW(orderedTasks(
                   50, 4, [](long) { return false; }, [](long) {},
                   [&](long k) {
                     if (k == 7) throw std::logic_error("commit");
                     committed.push_back(k);
                   }),
               std::logic_error);
  EXPECT_EQ(committed.size(), 7u);
}

}  // namespace
}  // namespace metrosync
