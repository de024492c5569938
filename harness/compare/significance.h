#pragma once
// Statistics for comparing two sets of per-frame timings (lodbench compare, docs/design.md, Reports and regression
// checks).
#include <cstdint>
#include <vector>

namespace lb {

struct MannWhitney {
  double u = 0;  // U of the first sample: pairs (x_i, y_j) with x_i > y_j, ties counting 1/2
  double z = 0;  // standardised max(U1, U2) after the continuity correction; 0 when undefined
  double p = 1;  // two-sided p-value; 1 when either sample is empty or every value is tied
};

// Two-sided Mann-Whitney U test with the normal approximation, tie correction of the variance and
// continuity correction: the same figures as scipy.stats.mannwhitneyu(x, y, alternative="two-sided",
// method="asymptotic"). Valid for the sample sizes we use (tens to thousands of frames each).
MannWhitney mannWhitneyU(const std::vector<double>& x, const std::vector<double>& y);

struct RatioInterval {
  double ratio = 0;       // median(candidate) / median(baseline)
  double lo = 0, hi = 0;  // percentile bootstrap interval of that ratio
};

// Percentile bootstrap of the ratio of medians: each side is resampled with replacement on its own,
// `resamples` times, and the (1 - confidence) / 2 tails of the resampled ratios are cut. The random
// stream is splitmix64 from `seed`, so the same inputs give the same interval on every machine.
// Precondition (asserted): both samples non-empty with a positive baseline median.
RatioInterval bootstrapMedianRatio(const std::vector<double>& baseline, const std::vector<double>& candidate,
                                   double confidence, int resamples = 2000, uint64_t seed = 0x10DBE7C4);

double median(std::vector<double> values);

// Two-sided p-value of Student's t with df degrees of freedom (regularized incomplete beta).
double studentTwoSidedP(double t, double df);
// t such that P(|T| > t) = 1 - confidence.
double studentQuantile(double confidence, double df);

// Timing evidence from rounds (one median GPU ms per run): the rounds are the samples, since
// frames of one run share its clock, caches and neighbours and are not independent. On the log of
// the round medians: Welch's t-test, or with paired rounds (A/B mode: round i of each side ran side
// by side) a paired t-test on the per-pair log ratios. ratio = exp(mean log difference), the
// geometric-mean ratio, with its t interval at `confidence`.
struct RoundTest {
  double ratio = 0, lo = 0, hi = 0;
  double t = 0, df = 0;
  double p = 1;
};
RoundTest roundTest(const std::vector<double>& baselineRounds, const std::vector<double>& candidateRounds, bool paired,
                    double confidence);

}  // namespace lb
