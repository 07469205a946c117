// The statistics behind rates, medians and `tcbench compare`, against known
// values: Wilson intervals as tabulated (and as the report computes them),
// the bootstrap against an independent Python transcription of its
// definition (report/tcbench_report/statistics.py must print the same), the
// U test against the textbook normal approximation.
#include <catch2/catch.hpp>

#include "experiments/statistics/bootstrap_interval.hpp"
#include "experiments/statistics/mann_whitney.hpp"
#include "experiments/statistics/wilson_interval.hpp"
#include "sim/random/counter_random.hpp"

using namespace tcb;

TEST_CASE("wilson interval: known values, inside [0, 1], none without runs", "[statistics]") {
  CHECK_FALSE(wilson_interval(0, 0));
  const Interval none = *wilson_interval(0, 10);
  CHECK(none.lo == 0.0);
  CHECK(none.hi == Approx(0.2775327998628892).epsilon(1e-12));  // the "rule of three" region: 0/10 is not 0
  const Interval half = *wilson_interval(5, 10);
  CHECK(half.lo == Approx(0.236593090512564).epsilon(1e-12));
  CHECK(half.hi == Approx(0.7634069094874361).epsilon(1e-12));
  const Interval all = *wilson_interval(10, 10);
  CHECK(all.lo == Approx(0.7224672001371107).epsilon(1e-12));
  CHECK(all.hi == 1.0);
  const Interval four_of_five = *wilson_interval(4, 5);
  CHECK(four_of_five.lo == Approx(0.37553462976252533).epsilon(1e-12));
  CHECK(four_of_five.hi == Approx(0.9637758913675698).epsilon(1e-12));
}

TEST_CASE("uniform_01: the top 53 bits times 2^-53", "[statistics][random]") {
  CHECK(uniform_01(0, 0, 0) == 0.13870941014555427);  // independent Python transcription
  CHECK(uniform_01(0, 0, 0) == 0.5 * (uniform_pm1(0, 0, 0) + 1.0));
}

TEST_CASE("median and bootstrap interval: the documented definition, reproducible", "[statistics]") {
  CHECK(std::isnan(median_of({})));
  CHECK(median_of({3.0}) == 3.0);
  CHECK(median_of({4.0, 1.0}) == 2.5);
  CHECK(median_of({5.0, 1.0, 3.0}) == 3.0);
  const MedianEstimate one = bootstrap_median({2.0});
  CHECK(one.median == 2.0);
  CHECK_FALSE(one.ci95);
  const MedianEstimate tied = bootstrap_median({1.5, 1.5, 1.5, 1.5});
  REQUIRE(tied.ci95);
  CHECK(tied.ci95->lo == 1.5);
  CHECK(tied.ci95->hi == 1.5);
  // The reference values of report/tcbench_report/statistics.py and of an
  // independent transcription: every build prints the same interval.
  const MedianEstimate e = bootstrap_median({3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0, 6.0});
  CHECK(e.median == 3.5);
  CHECK(e.n == 8);
  REQUIRE(e.ci95);
  CHECK(e.ci95->lo == 1.0);
  CHECK(e.ci95->hi == 6.0);
  const MedianEstimate d = bootstrap_median_difference({3.0, 1.0, 4.0, 1.0, 5.0}, {9.0, 2.0, 6.0, 5.0, 3.0, 5.0});
  CHECK(d.median == 2.0);
  REQUIRE(d.ci95);
  CHECK(d.ci95->lo == -1.0);
  CHECK(d.ci95->hi == 5.0);
  CHECK_FALSE(bootstrap_median_difference({1.0}, {2.0, 3.0}).ci95);
  // Identical samples: the difference's interval holds 0.
  const std::vector<double> same = {1.0, 2.0, 3.0, 4.0, 5.0};
  const MedianEstimate zero = bootstrap_median_difference(same, same);
  CHECK(zero.median == 0.0);
  CHECK(zero.ci95->lo <= 0.0);
  CHECK(zero.ci95->hi >= 0.0);
}

TEST_CASE("Mann-Whitney U: separated samples, ties, and all tied", "[statistics]") {
  const MannWhitney apart = *mann_whitney({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  CHECK(apart.u_a == 0.0);
  CHECK(apart.a_greater_share == 0.0);
  CHECK(apart.p_two_sided == Approx(0.012185780355344818).epsilon(1e-9));  // z = 12 / sqrt(22.917)
  CHECK(mann_whitney({6, 7, 8, 9, 10}, {1, 2, 3, 4, 5})->p_two_sided == Approx(apart.p_two_sided));
  const MannWhitney ties = *mann_whitney({1, 2, 2, 3}, {2, 3, 4, 5});
  CHECK(ties.u_a == 2.5);
  CHECK(ties.p_two_sided == Approx(0.13665824773814753).epsilon(1e-9));
  CHECK(mann_whitney({2, 2, 2}, {2, 2})->p_two_sided == 1.0);
  CHECK_FALSE(mann_whitney({}, {1.0}));
}
