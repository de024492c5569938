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

std::string scenarioAnswer(const std::string& scenario, const std::vector<Point>& points, size_t timedOnly) {
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
  s += name(fast);
  s += ". Most accurate within " + formatValue(gpuCap) + " ms of GPU time (the median): ";
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

std::string deviceCaveat(const ReportRun& run) {
  auto it = run.context.find("device");
  const std::string device =
      it != run.context.end() && it->is_string() ? it->get<std::string>() : "an unrecorded device";
  std::string s = "Caveat: the GPU times come from " + device + " and rank the schemes on that device only";
  std::string lower = device;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  if (lower.find("llvmpipe") != std::string::npos || lower.find("lavapipe") != std::string::npos ||
      lower.find("swiftshader") != std::string::npos)
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
    out.push_back(scenarioAnswer(scenario, points, timedOnly));
  }
  if (!anyOk) return {"No case finished, so this report has no figures to answer from (see Failed and skipped cases)."};
  out.push_back(deviceCaveat(run));
  return out;
}

}  // namespace lb
