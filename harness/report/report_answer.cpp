#include "report/report_answer.h"

#include <algorithm>

namespace lb {

namespace {

struct Point {
  const ReportCase* c;
  double gpu, err;
  std::optional<double> tris;
};

std::string describe(const Point& p) {
  std::string s = p.c->label + " (case " + p.c->id + "): " + formatValue(p.gpu) + " ms median GPU time, " +
                  formatValue(p.err) + " px mean error";
  if (p.tris) s += ", " + formatValue(*p.tris) + " triangles";
  return s;
}

// The point with the lowest `key` among those `admit` lets in (first in case order on ties).
template <class Admit, class Key>
const Point* best(const std::vector<Point>& points, Admit admit, Key key) {
  const Point* b = nullptr;
  for (const Point& p : points)
    if (admit(p) && (!b || key(p) < key(*b))) b = &p;
  return b;
}

// The median GPU time of each repetition: frames are stored repetition after repetition
// (docs/results-format.md), so `reps` equal slices; one value when they do not split evenly.
std::vector<double> repetitionMedians(const ReportCase& c, int reps) {
  std::vector<double> all;
  for (auto& f : c.frames)
    if (auto v = frameValue(f, "gpu_ms")) all.push_back(*v);
  if (all.empty()) return {};
  if (reps < 2 || all.size() % size_t(reps) != 0 || all.size() / size_t(reps) == 0) return {medianOf(all)};
  std::vector<double> out;
  const size_t per = all.size() / size_t(reps);
  for (int r = 0; r < reps; ++r)
    out.push_back(
        medianOf(std::vector<double>(all.begin() + long(size_t(r) * per), all.begin() + long((r + 1) * per))));
  return out;
}

// How far the fastest case leads the fastest case of any other scheme under the same cap, and
// whether that lead is larger than the noise between repetitions.
std::string marginSentence(const Point& fast, const std::vector<Point>& points, double errCap, int reps) {
  const Point* second = best(
      points, [&](const Point& p) { return p.err <= errCap && p.c->scheme != fast.c->scheme; },
      [](const Point& p) { return p.gpu; });
  if (!second) return " No other scheme has a case within that error, so there is no runner-up to measure a margin to.";
  const double margin = second->gpu - fast.gpu;
  std::string s = " Runner-up, the fastest other scheme within that error: " + second->c->label + " at " +
                  formatValue(second->gpu) + " ms, a margin of " + formatValue(margin) + " ms (" +
                  formatValue(fast.gpu > 0 ? 100 * margin / fast.gpu : 0) + "%)";
  std::vector<double> a = repetitionMedians(*fast.c, reps), b = repetitionMedians(*second->c, reps);
  if (a.size() < 2 || b.size() < 2)
    return s + "; the run has " + (reps < 2 ? "one repetition" : "no per-repetition frames") +
           ", so there is no run-to-run spread to judge the margin by (set repetitions to 3 or more).";
  auto spread = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
  };
  const double noise = std::max(spread(a), spread(b));
  const std::string rule =
      " (rule: the margin against the larger of the two cases' run-to-run spreads, max - min of "
      "their " +
      std::to_string(reps) + " per-repetition medians, here " + formatValue(noise) + " ms)";
  return s + (margin < noise ? ": within noise" + rule + ", so the two are not told apart."
                             : ": larger than the noise" + rule + ".");
}

std::string scenarioAnswer(const std::string& scenario, const std::vector<Point>& points, size_t timedOnly, int reps) {
  std::string lead = scenario + ": ";
  if (points.empty())
    return lead + "no finished case has both a GPU time and an error pass (config measure.passes lacks \"error\"), " +
           "so this report cannot say which scheme is fastest at a given accuracy" +
           (timedOnly ? " (" + std::to_string(timedOnly) + " cases have timings only)." : ".");
  std::vector<double> errs, gpus, tris;
  for (const Point& p : points) {
    errs.push_back(p.err);
    gpus.push_back(p.gpu);
    if (p.tris) tris.push_back(*p.tris);
  }
  const double errCap = medianOf(errs), gpuCap = medianOf(gpus);
  const std::string n = std::to_string(points.size()) + " case" + (points.size() == 1 ? "" : "s");
  const Point* fast = best(
      points, [&](const Point& p) { return p.err <= errCap; }, [](const Point& p) { return p.gpu; });
  const Point* exact = best(
      points, [&](const Point& p) { return p.gpu <= gpuCap; }, [](const Point& p) { return p.err; });
  // A case named before is not described twice.
  std::vector<const Point*> named;
  auto name = [&](const Point* p) {
    if (std::find(named.begin(), named.end(), p) != named.end()) return p->c->label + " again";
    named.push_back(p);
    return describe(*p);
  };
  // Named in reading order (the operands of + are unsequenced: one statement per name).
  std::string s = lead + n + " with an error pass. Fastest at a mean screen-space error of at most " +
                  formatValue(errCap) + " px (the median error): ";
  s += name(fast) + ".";
  s += marginSentence(*fast, points, errCap, reps);
  s += " Most accurate within " + formatValue(gpuCap) + " ms of GPU time (the median): ";
  s += name(exact) + ".";
  if (tris.size() == points.size()) {
    const double triCap = medianOf(tris);
    const Point* lean = best(
        points, [&](const Point& p) { return *p.tris <= triCap; }, [](const Point& p) { return p.err; });
    s += " Most accurate within " + formatValue(triCap) +
         " triangles (the median; triangle counts do not depend on the device): ";
    s += name(lean) + ".";
  }
  if (timedOnly) s += " Not counted: " + std::to_string(timedOnly) + " finished case(s) without an error pass.";
  return s;
}

int repetitions(const ReportRun& run) {
  auto config = run.context.find("config");
  if (config == run.context.end() || !config->is_object()) return 1;
  auto r = config->find("repetitions");
  return r != config->end() && r->is_number_integer() ? std::max(1, r->get<int>()) : 1;
}

}  // namespace

bool softwareRasterizer(const std::string& device) {
  std::string lower = device;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  return lower.find("llvmpipe") != std::string::npos || lower.find("lavapipe") != std::string::npos ||
         lower.find("swiftshader") != std::string::npos;
}

namespace {

std::string deviceCaveat(const ReportRun& run) {
  auto it = run.context.find("device");
  const std::string device =
      it != run.context.end() && it->is_string() ? it->get<std::string>() : "an unrecorded device";
  std::string s = "Caveat: the GPU times come from " + device + " and rank the schemes on that device only";
  if (softwareRasterizer(device))
    s += " (a software rasterizer on the CPU: its costs do not predict a hardware GPU's; tessellation is "
         "emulated on the CPU there, so timings across draw paths, tessellated against instanced, are no "
         "verdict on the tessellator)";
  return s +
         "; errors and triangle counts do not depend on the device. Thresholds are the medians of this run's "
         "cases, so they move with the sweep; the charts below show every case.";
}

}  // namespace

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

std::vector<std::string> openingAnswer(const ReportRun& run) {
  std::vector<std::string> out;
  bool anyOk = false;
  for (const std::string& scenario : run.scenarios) {
    std::vector<Point> points;
    size_t timedOnly = 0, ok = 0;
    for (const ReportCase& c : run.cases) {
      if (c.scenario != scenario || c.status != "ok") continue;
      ++ok;
      auto gpu = summaryStat(c.summary, "gpu_ms", "median");
      auto err = summaryStat(c.summary, "err_mean_px", "mean");
      if (gpu && err)
        points.push_back({&c, *gpu, *err, summaryStat(c.summary, "triangles", "median")});
      else if (gpu)
        ++timedOnly;
    }
    if (ok == 0) continue;  // every case failed or was skipped: the problems table says why
    anyOk = true;
    out.push_back(scenarioAnswer(scenario, points, timedOnly, repetitions(run)));
  }
  if (!anyOk) return {"No case finished, so this report has no figures to answer from (see Failed and skipped cases)."};
  out.push_back(deviceCaveat(run));
  return out;
}

}  // namespace lb
