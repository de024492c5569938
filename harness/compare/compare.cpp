#include "compare/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "compare/significance.h"
#include "error.h"
#include "metrics/coverage.h"

namespace lb {

using nlohmann::json;

const char* const kTimingMethod =
    "rounds are the samples (frames of one run share its clock, caches and load and are not independent): each "
    "round's median GPU ms; ratio = exp(mean(log candidate rounds) - mean(log baseline rounds)) with a Student t "
    "interval at confidence 1 - alpha; p: Welch's t-test on the log round medians (A/B mode: paired t-test on the "
    "per-pair log ratios); a verdict needs at least 3 rounds per side, else the ratio of the round medians' medians "
    "is reported without one";

namespace {

// Deterministic per-frame figures: equal on the same device and driver, whatever the timing.
const char* const kCounterFields[] = {"patches", "tes_invocations", "clip_invocations", "clip_primitives",
                                      "fragment_invocations"};
// Counters that runs from before the draw paths lack: compared where the baseline has them.
const char* const kNewerCounterFields[] = {"instances", "draws"};

bool isExactMeasurement(const std::string& key) {
  return key.rfind("hist", 0) == 0 || key == "cracks_analytic" || key == "cracks_pixels" ||
         key.rfind("coverage_", 0) == 0;
}

struct AccuracyMetric {
  const char* name;
  bool higherIsWorse;
  double slack;  // allowed beyond the relative tolerance, in the metric's unit
};
// Coverage counts pixels: across devices a silhouette may rasterize a pixel apart, so a case's mean
// may move by up to kCoverageSlackPx (on one device the exact check compares every frame's count).
const AccuracyMetric kAccuracyMetrics[] = {{"err_mean_px", true, 1e-12},
                                           {"err_p95_px", true, 1e-12},
                                           {"img_psnr_db", false, 1e-12},
                                           {"img_ssim", false, 1e-12},
                                           {"flip_mean", true, 1e-12},
                                           {"coverage_missing_px", true, kCoverageSlackPx},
                                           {"coverage_extra_px", true, kCoverageSlackPx}};

// First record of each frame index (repetitions replay the same frames; their counters are equal).
std::map<int, const json*> byFrame(const json& frames) {
  std::map<int, const json*> m;
  for (auto& f : frames)
    if (f.contains("frame") && f["frame"].is_number_integer()) m.emplace(f["frame"].get<int>(), &f);
  return m;
}

// First differing field of one frame ("" when equal); fills both values.
std::string firstDifference(const json& b, const json& c, std::string& bv, std::string& cv,
                            std::vector<std::string>& fields) {
  std::string first;
  auto note = [&](const std::string& field, const json& x, const json& y) {
    if (first.empty()) {
      first = field;
      bv = x.dump();
      cv = y.dump();
    }
    std::string name = field.substr(0, field.find('['));
    if (std::find(fields.begin(), fields.end(), name) == fields.end()) fields.push_back(name);
  };
  static const json kAbsent = "absent";
  for (const char* f : kCounterFields) {
    const json& x = b.contains(f) ? b[f] : kAbsent;
    const json& y = c.contains(f) ? c[f] : kAbsent;
    if (x != y) note(f, x, y);
  }
  for (const char* f : kNewerCounterFields)
    if (b.contains(f) && (!c.contains(f) || b[f] != c[f])) note(f, b[f], c.contains(f) ? c[f] : kAbsent);
  // A measurement the baseline has and the candidate lacks (or has as null) is a difference: a
  // pass that stopped working must not pass as "nothing to compare".
  for (auto& [key, x] : b.items()) {
    if (!isExactMeasurement(key)) continue;
    const json& y = c.contains(key) ? c[key] : kAbsent;
    if (x.is_array() && y.is_array() && x.size() == y.size()) {
      for (size_t i = 0; i < x.size(); ++i)
        if (x[i] != y[i]) {
          note(key + "[" + std::to_string(i) + "]", x[i], y[i]);
          break;
        }
    } else if (x != y) {
      note(key, x, y);
    }
  }
  return first;
}

bool compareExact(const CaseData& b, const CaseData& c, ExactDiff& d) {
  auto fb = byFrame(b.frames), fc = byFrame(c.frames);
  bool differs = false;
  for (auto& [frame, rb] : fb) {
    auto it = fc.find(frame);
    if (it == fc.end()) continue;
    std::string bv, cv;
    std::string field = firstDifference(*rb, *it->second, bv, cv, d.fields);
    if (field.empty()) continue;
    if (!differs) {
      d.frame = frame;
      d.field = field;
      d.baseline = bv;
      d.candidate = cv;
    }
    differs = true;
    d.framesDiffering++;
  }
  auto range = [](const std::map<int, const json*>& m) {
    return m.empty() ? std::string("0 frames")
                     : std::to_string(m.size()) + " frames (" + std::to_string(m.begin()->first) + ".." +
                           std::to_string(m.rbegin()->first) + ")";
  };
  bool sameFrames = fb.size() == fc.size() &&
                    std::equal(fb.begin(), fb.end(), fc.begin(), [](auto& x, auto& y) { return x.first == y.first; });
  if (!sameFrames) {
    if (!differs) {
      d.frame = -1;
      d.field = "frames";
      d.baseline = range(fb);
      d.candidate = range(fc);
    }
    d.fields.push_back("frames");
    differs = true;
  }
  return differs;
}

void compareTiming(const CaseData& b, const CaseData& c, const CompareOptions& o, TimingCheck& t) {
  t.nBaseline = int(b.gpuMs.size());
  t.nCandidate = int(c.gpuMs.size());
  t.roundsBaseline = int(b.roundMedians.size());
  t.roundsCandidate = int(c.roundMedians.size());
  if (b.roundMedians.empty() || c.roundMedians.empty()) {
    t.reason = "no timing frames on a side";
    return;
  }
  t.baselineMs = median(b.roundMedians);
  t.candidateMs = median(c.roundMedians);
  if (!(t.baselineMs > 0) || !(t.candidateMs > 0)) {
    t.reason = "a median GPU time is 0 (no timestamps on its device)";
    return;
  }
  t.ratio = t.candidateMs / t.baselineMs;
  const int need = std::max(2, o.minRounds);
  if (t.roundsBaseline < need || t.roundsCandidate < need) {
    t.reason = "no timing verdict: " + std::to_string(t.roundsBaseline) + " baseline and " +
               std::to_string(t.roundsCandidate) + " candidate round(s), a verdict needs " + std::to_string(need) +
               " per side (frames of one run are not independent samples); ratio reported only";
    return;
  }
  t.pairedRounds = o.pairedRounds && t.roundsBaseline == t.roundsCandidate;
  for (double v : b.roundMedians)
    if (!(v > 0)) {
      t.reason = "a baseline round has no positive median GPU time";
      return;
    }
  for (double v : c.roundMedians)
    if (!(v > 0)) {
      t.reason = "a candidate round has no positive median GPU time";
      return;
    }
  RoundTest rt = roundTest(b.roundMedians, c.roundMedians, t.pairedRounds, 1.0 - o.alpha);
  t.ratio = rt.ratio;
  t.lo = rt.lo;
  t.hi = rt.hi;
  t.p = rt.p;
  bool significant = t.p < o.alpha;
  if (significant && t.ratio > 1.0 + o.threshold)
    t.verdict = TimingVerdict::Regression;
  else if (significant && t.ratio < 1.0 / (1.0 + o.threshold))
    t.verdict = TimingVerdict::Improvement;
  else
    t.verdict = TimingVerdict::Unchanged;
}

// The mean over measured frames from a summary statistics object (or a plain number).
bool summaryValue(const json& summary, const char* key, double& v) {
  if (!summary.contains(key)) return false;
  const json& s = summary[key];
  if (s.is_object() && s.contains("mean") && s["mean"].is_number()) {
    v = s["mean"].get<double>();
    return true;
  }
  if (s.is_number()) {
    v = s.get<double>();
    return true;
  }
  return false;
}

std::string fmt(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);
  return s;
}

void compareAccuracy(const CaseData& b, const CaseData& c, const CompareOptions& o, CaseComparison& cc) {
  for (auto& m : kAccuracyMetrics) {
    AccuracyCheck a;
    a.metric = m.name;
    a.higherIsWorse = m.higherIsWorse;
    if (!summaryValue(b.summary, m.name, a.baseline)) continue;
    if (!summaryValue(c.summary, m.name, a.candidate)) {  // measured before, not now: a regression
      cc.regressions.push_back(std::string(m.name) + " present in the baseline, missing in the candidate");
      continue;
    }
    double allowed = o.errorTolerance * std::abs(a.baseline) + m.slack;
    a.worse = m.higherIsWorse ? a.candidate > a.baseline + allowed : a.candidate < a.baseline - allowed;
    cc.accuracy.push_back(a);
  }
  // Terrain missing from (or added to) a frame beyond metrics/coverage.h's tolerance fails the case
  // whatever the baseline says: such a frame's err_* may be null and leave every mean above.
  auto failed = c.summary.find("coverage_failed_frames");
  if (failed != c.summary.end() && failed->is_array() && !failed->empty()) {
    std::string frames;
    for (auto& f : *failed) frames += (frames.empty() ? "" : ", ") + f.dump();
    cc.regressions.push_back("coverage: frame(s) " + frames + " miss or add more than " +
                             fmt(kCoverageTolerance * 100) + "% of the truth's terrain pixels");
  }
}

std::string ctxString(const json& ctx, const char* key) {
  return ctx.contains(key) && ctx[key].is_string() ? ctx[key].get<std::string>() : "";
}

}  // namespace

const char* timingVerdictName(TimingVerdict v) {
  switch (v) {
    case TimingVerdict::Unchanged:
      return "unchanged";
    case TimingVerdict::Regression:
      return "regression";
    case TimingVerdict::Improvement:
      return "improvement";
    default:
      return "not checked";
  }
}

int CompareReport::regressions() const {
  return int(std::count_if(cases.begin(), cases.end(), [](auto& c) { return !c.regressions.empty(); }));
}

int CompareReport::improvements() const {
  return int(std::count_if(cases.begin(), cases.end(), [](auto& c) { return c.improved; }));
}

CompareReport compareRuns(const RunData& base, const RunData& cand, const CompareOptions& o) {
  CompareReport r;
  r.baselineDir = base.dir;
  r.candidateDir = cand.dir;
  r.baselineContext = base.context;
  r.candidateContext = cand.context;
  r.options = o;

  // Counters are deterministic per device and driver build only (docs/design.md, Renderer).
  const char* const identity[] = {"device", "driver", "driver_info"};
  r.exactChecked = true;
  for (const char* key : identity) {
    std::string b = ctxString(base.context, key), c = ctxString(cand.context, key);
    if (b.empty() || c.empty() || b != c) {
      r.exactChecked = false;
      r.exactSkipReason = std::string("context.") + key + " differs: '" + b + "' (baseline) vs '" + c +
                          "' (candidate); counters are only comparable on the same device and driver";
      break;
    }
  }
  if (!r.exactChecked) {
    if (o.requireExact) throw InputError("compare --require-exact: counters cannot be compared: " + r.exactSkipReason);
    r.notChecked.push_back("exact counters and deterministic measurements were NOT checked: " + r.exactSkipReason);
  }
  if (ctxString(base.context, "device") != ctxString(cand.context, "device"))
    r.notes.push_back("timings come from different devices: ratios compare devices, not code");
  // Two boards of one model: counters stay comparable, timings carry the board-to-board spread.
  else if (std::string b = ctxString(base.context, "device_uuid"), c = ctxString(cand.context, "device_uuid");
           !b.empty() && !c.empty() && b != c)
    r.notes.push_back("timings come from two boards of one model (device_uuid " + b + " (baseline) vs " + c +
                      " (candidate)): ratios include the boards' own difference");
  for (const char* k : {"power_limit_w", "power_limit_enforced_w"})
    if (base.context.contains(k) && cand.context.contains(k) && base.context[k].is_number() &&
        cand.context[k].is_number() && base.context[k] != cand.context[k])
      r.notes.push_back(std::string("the boards ran under different power limits (") + k + " " +
                        base.context[k].dump() + " W (baseline) vs " + cand.context[k].dump() + " W (candidate))");
  if (cand.testSlowdown > 0)
    r.notes.push_back("the candidate ran with a planted test slowdown of " + fmt(cand.testSlowdown) +
                      " (run --test-slowdown)");
  for (auto [side, run] : {std::pair{"baseline", &base}, std::pair{"candidate", &cand}})
    if (run->context.contains("validation") && run->context["validation"] == true)
      r.notes.push_back(std::string("the ") + side +
                        " ran with the validation layer on: its timings include its overhead");
  if (base.testSlowdown > 0)
    r.notes.push_back("the baseline ran with a planted test slowdown of " + fmt(base.testSlowdown));

  for (auto& [id, b] : base.cases)
    if (!cand.cases.count(id)) r.onlyInBaseline.push_back(id);
  for (auto& [id, c] : cand.cases)
    if (!base.cases.count(id)) r.onlyInCandidate.push_back(id);

  for (auto& [id, b] : base.cases) {
    auto it = cand.cases.find(id);
    if (it == cand.cases.end()) continue;
    const CaseData& c = it->second;
    CaseComparison cc;
    cc.id = id;
    cc.baselineStatus = b.status;
    cc.candidateStatus = c.status;
    for (const char* key : {"lod_ms", "draw_ms", "lod_cpu_ms"}) {
      auto median = [&](const nlohmann::json& s) -> const nlohmann::json* {
        auto it = s.find(key);
        if (it == s.end() || !it->is_object() || !it->contains("median") || !(*it)["median"].is_number())
          return nullptr;
        return &(*it)["median"];
      };
      if (const nlohmann::json* x = median(b.summary), *y = median(c.summary); x && y)
        cc.split.push_back({key, x->get<double>(), y->get<double>()});
    }
    if (b.status == "ok" && c.status != "ok") {
      cc.regressions.push_back("case " + c.status + " in the candidate: " + c.reason);
    } else if (b.status != "ok" && c.status == "ok") {
      cc.improved = true;
      cc.statusNote = "was " + b.status + " in the baseline, ok now";
    } else if (b.status != "ok") {
      cc.statusNote = "not ok on either side (" + b.status + " / " + c.status + "): not compared";
    }
    if (b.status == "ok" && c.status == "ok") {
      if (r.exactChecked) {
        cc.exactChecked = true;
        cc.exactDiffers = compareExact(b, c, cc.exact);
        if (cc.exactDiffers)
          cc.regressions.push_back(
              cc.exact.frame < 0 ? "frame set differs: " + cc.exact.baseline + " vs " + cc.exact.candidate
                                 : "exact figures differ: first at frame " + std::to_string(cc.exact.frame) + ", " +
                                       cc.exact.field + " " + cc.exact.baseline + " -> " + cc.exact.candidate);
      }
      compareTiming(b, c, o, cc.timing);
      if (cc.timing.verdict == TimingVerdict::Regression)
        cc.regressions.push_back("GPU time x" + fmt(cc.timing.ratio) + " [" + fmt(cc.timing.lo) + ", " +
                                 fmt(cc.timing.hi) + "], p = " + fmt(cc.timing.p));
      if (cc.timing.verdict == TimingVerdict::Improvement) cc.improved = true;
      compareAccuracy(b, c, o, cc);
      for (auto& a : cc.accuracy)
        if (a.worse) cc.regressions.push_back(a.metric + " worse: " + fmt(a.baseline) + " -> " + fmt(a.candidate));
    }
    r.cases.push_back(std::move(cc));
  }
  int noVerdict = 0;
  std::string why;
  for (auto& cc : r.cases)
    if (cc.baselineStatus == "ok" && cc.candidateStatus == "ok" && cc.timing.verdict == TimingVerdict::NotChecked) {
      ++noVerdict;
      if (why.empty()) why = cc.timing.reason;
    }
  if (noVerdict)
    r.notChecked.push_back("timing was NOT judged for " + std::to_string(noVerdict) + " of " +
                           std::to_string(r.cases.size()) + " cases (" + why + ")");
  if (!r.onlyInBaseline.empty())
    r.notChecked.push_back(std::to_string(r.onlyInBaseline.size()) +
                           " baseline case(s) are missing in the candidate and were NOT compared" +
                           (o.requireExact ? " (a regression with --require-exact)" : ""));
  return r;
}

}  // namespace lb
