// sim/record/sample_ring.h: first in, first out, across growth and wrap-around, against a deque.
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <vector>

#include "sim/record/sample_ring.h"

namespace metrosync {
namespace {

TEST(SampleRing, BehavesAsAQueueOfSamplesThroughGrowthAndWrapAround) {
  constexpr int kWidth = 3;  // two parts: 1 value and 2 values
  SampleRing ring(kWidth);
  std::deque<std::vector<double>> model;  // t, then the values
  std::mt19937 rng(5);
  double t = 0.0;
  for (int op = 0; op < 5000; ++op) {
    // pushes win on average, with long runs of pops, so the ring grows and wraps many times
    const bool push = model.empty() || (rng() % 100) < (op % 700 < 350 ? 70 : 35);
    if (push) {
      t += 1.0;
      const double a[1] = {t * 2}, b[2] = {t * 3, -t};
      ring.push(t, {a, b}, {1, 2});
      model.push_back({t, a[0], b[0], b[1]});
    } else {
      ring.popFront();
      model.pop_front();
    }
    ASSERT_EQ(ring.size(), model.size());
    for (size_t k : {size_t{0}, model.size() / 2, model.size() - 1}) {
      if (model.empty()) break;
      ASSERT_EQ(ring.time(k), model[k][0]) << "op " << op << " k " << k;
      for (int v = 0; v < kWidth; ++v) ASSERT_EQ(ring.values(k)[v], model[k][1 + v]);
    }
  }
}

}  // namespace
}  // namespace metrosync
