// The bytes between MPI ranks (tools/cli/sweep_messages.h): a point survives the trip bit for
// bit (NaN, inf, -0, texts with commas and newlines), and bytes that are not a message are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "tools/cli/sweep_messages.h"

namespace {

using namespace metrosync;
using namespace metrosync::cli;

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

SweepPoint oddPoint(long g) {
  SweepPoint p;
  p.index = g;
  p.regime = "failed";
  p.A = {1.0 / 3.0, std::nan(""), -0.0};
  p.psi = {std::nextafter(2 * M_PI, 0.0), std::numeric_limits<double>::denorm_min()};
  p.r = std::numeric_limits<double>::quiet_NaN();
  p.s = std::numeric_limits<double>::infinity();
  p.clusters = "2+1";
  p.tau = 1e300;
  p.complete = false;
  p.message = "stopped at t = 3: \"bad\",\nnext line";
  p.in_phase_fraction = 0.375;
  p.wall_seconds = 0.125;
  p.cpu_seconds = 0.0625;
  p.engine_cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  return p;
}

TEST(SweepMessages, AReportCarriesEveryBitOfItsPoints) {
  SweepReport r;
  r.want = 7;
  r.points = {oddPoint(3), oddPoint(10000000 - 1)};
  r.points[1].A.clear();
  r.unrun = {5, 9};
  const SweepReport back = decodeReport(encodeReport(r));
  EXPECT_EQ(back.want, 7);
  EXPECT_FALSE(back.done);
  EXPECT_EQ(back.unrun, r.unrun);
  ASSERT_EQ(back.points.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const SweepPoint &a = r.points[k], &b = back.points[k];
    EXPECT_EQ(b.index, a.index);
    EXPECT_EQ(b.regime, a.regime);
    ASSERT_EQ(b.A.size(), a.A.size());
    for (size_t i = 0; i < a.A.size(); ++i) EXPECT_TRUE(sameBits(a.A[i], b.A[i])) << i;
    ASSERT_EQ(b.psi.size(), a.psi.size());
    for (size_t i = 0; i < a.psi.size(); ++i) EXPECT_TRUE(sameBits(a.psi[i], b.psi[i])) << i;
    EXPECT_TRUE(sameBits(a.r, b.r));
    EXPECT_TRUE(sameBits(a.s, b.s));
    EXPECT_TRUE(sameBits(a.tau, b.tau));
    EXPECT_TRUE(sameBits(a.in_phase_fraction, b.in_phase_fraction));  // --basin-samples
    EXPECT_TRUE(sameBits(a.wall_seconds, b.wall_seconds));
    EXPECT_TRUE(sameBits(a.cpu_seconds, b.cpu_seconds));
    EXPECT_TRUE(sameBits(a.engine_cpu_seconds, b.engine_cpu_seconds));
    EXPECT_EQ(b.clusters, a.clusters);
    EXPECT_EQ(b.complete, a.complete);
    EXPECT_EQ(b.message, a.message);
  }
}

TEST(SweepMessages, WorkRoundTripsAndGarbageIsRefused) {
  const SweepWork w{true, {0, 1, 143}};
  const SweepWork back = decodeWork(encodeWork(w));
  EXPECT_TRUE(back.last);
  EXPECT_EQ(back.indices, w.indices);
  const std::string bytes = encodeReport(SweepReport{2, true, {oddPoint(1)}, {}});
  EXPECT_TRUE(decodeReport(bytes).done);
  for (size_t cut : {size_t{0}, size_t{5}, bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(decodeReport(bytes.substr(0, cut)), std::runtime_error) << cut;
  EXPECT_THROW(decodeReport(bytes + "x"), std::runtime_error);
  EXPECT_THROW(decodeWork(std::string(9, '\xff')), std::runtime_error);
}

}  // namespace
