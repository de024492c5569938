#include "sweep/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "camera/camera_path.h"
#include "config/config.h"

namespace lb {

std::vector<CaseWork> plannedWork(const Config& config, const std::vector<Case>& cases) {
  std::map<std::string, int> framesOf;  // per path file
  std::set<std::string> truthMade;      // terrain, path and resolution whose truth an earlier case makes
  const bool truth = config.measure.on("image") || config.measure.on("cracks");
  int modes = 1;  // shaded, plus one replay per other timing mode (replay/timing_passes.h)
  for (const std::string& m : config.timing.modes) modes += m != "shaded";
  std::vector<CaseWork> out;
  for (const Case& c : cases) {
    auto it = framesOf.find(c.path);
    if (it == framesOf.end()) it = framesOf.emplace(c.path, frameCount(loadCameraPath(c.path), config.fps)).first;
    int frames = config.maxFrames > 0 ? std::min(it->second, config.maxFrames) : it->second;
    CaseWork w;
    w.scheme = c.scheme;
    w.timingFrames = (config.warmupFrames + frames * config.repetitions) * modes;
    w.measuredFrames = config.measure.every > 0 ? (frames + config.measure.every - 1) / config.measure.every : 0;
    std::string key = c.terrainLabel + "#" + c.terrainDigest + "|" + c.path + "|" + std::to_string(c.width) + "x" +
                      std::to_string(c.height);
    if (truth && truthMade.insert(key).second) w.truthFrames = w.measuredFrames;
    out.push_back(w);
  }
  return out;
}

void EtaEstimator::add(Sums& s, const std::string& scheme, long units, double seconds) {
  if (units <= 0 || !(seconds >= 0)) return;
  for (const std::string& key : {scheme, std::string()}) {
    s[key].seconds += seconds;
    s[key].units += units;
  }
}

double EtaEstimator::cost(const Sums& s, const std::string& scheme) {
  // A scheme's own cost once it has one: schemes differ several-fold (errbound's and the surplus
  // bisection's passes, uniform's triangle count), so the mean is only the fall-back.
  for (const std::string& key : {scheme, std::string()}) {
    auto it = s.find(key);
    if (it != s.end() && it->second.units > 0) return it->second.seconds / double(it->second.units);
  }
  return -1;
}

EtaEstimator::Own EtaEstimator::own(const std::string& scheme) const {
  auto one = [&](const Sums& s) {
    auto it = s.find(scheme);
    return it != s.end() && it->second.units > 0 ? it->second.seconds / double(it->second.units) : -1.0;
  };
  return {one(timing_), one(measured_), one(overhead_)};
}

void EtaEstimator::addTiming(const std::string& scheme, int frames, double seconds) {
  add(timing_, scheme, frames, seconds);
}
void EtaEstimator::addMeasured(const std::string& scheme, int frames, double seconds) {
  add(measured_, scheme, frames, seconds);
}
void EtaEstimator::addOverhead(const std::string& scheme, double seconds) {
  add(overhead_, scheme, 1, seconds);
}
void EtaEstimator::addTruth(int rayCasts, double seconds) {
  add(truth_, "", rayCasts, seconds);
}

double EtaEstimator::remaining(const std::vector<CaseWork>& work, bool& complete) const {
  complete = true;
  double total = 0;
  auto part = [&](double unitCost, long units) {
    if (units <= 0) return;
    if (unitCost < 0)
      complete = false;
    else
      total += unitCost * double(units);
  };
  for (const CaseWork& w : work) {
    part(timingCost(w.scheme), w.timingFrames);
    part(measuredCost(w.scheme), w.measuredFrames);
    part(overheadCost(w.scheme), w.overhead ? 1 : 0);
    part(truthCost(), w.truthFrames);
  }
  return total;
}

std::string formatDuration(double seconds) {
  char buf[48];
  long s = std::lround(std::max(0.0, seconds));
  if (s < 100)
    std::snprintf(buf, sizeof buf, "%ld s", s);
  else
    std::snprintf(buf, sizeof buf, "%ld min %ld s", s / 60, s % 60);
  return buf;
}

static double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// "~3 min 20 s left" or, before any case reached a part (the first case's measurement passes),
// "~40 s left + measurement passes (not timed yet)": never a figure that silently leaves work out.
static std::string leftText(double seconds, bool complete, bool measurementUnknown) {
  std::string s = "~" + formatDuration(seconds) + " left";
  if (!complete) s += measurementUnknown ? " + measurement passes (not timed yet)" : " + parts not timed yet";
  return s;
}

SweepProgress::SweepProgress(bool enabled, std::vector<CaseWork> cases, std::function<Truth()> truth)
    : enabled_(enabled), cases_(std::move(cases)), start_(Clock::now()), truth_(std::move(truth)) {}

double SweepProgress::leftAfterCurrent(bool& complete) const {
  std::vector<CaseWork> rest(cases_.begin() + long(std::min(cases_.size(), current_ + 1)), cases_.end());
  return eta_.remaining(rest, complete);
}

void SweepProgress::startCase(size_t index, const std::string& id) {
  current_ = index;
  caseStart_ = phaseStart_ = Clock::now();
  phase_ = Phase::Setup;
  timedSeconds_ = 0;
  phaseDone_ = 0;
  if (truth_) truthAtPhase_ = truth_();
  if (!enabled_) return;
  bool restComplete = true, caseComplete = true;
  double left = leftAfterCurrent(restComplete) + eta_.remaining({cases_[index]}, caseComplete);
  bool anyCost = eta_.timingCost("") >= 0;
  std::string bar(20, '.');
  std::fill(bar.begin(), bar.begin() + long(20 * index / std::max<size_t>(1, cases_.size())), '#');
  std::fprintf(stderr, "[%s] %zu/%zu %s  (%s elapsed%s)\n", bar.c_str(), index + 1, cases_.size(), id.c_str(),
               formatDuration(since(start_)).c_str(),
               anyCost ? (", " + leftText(left, restComplete && caseComplete, eta_.measuredCost("") < 0)).c_str() : "");
  std::fflush(stderr);
}

void SweepProgress::phase(Phase p) {
  double s = since(phaseStart_);
  const CaseWork& w = cases_[current_];
  // Ray casts made in this phase are the truth's cost, not the phase's.
  if (truth_) {
    Truth now = truth_();
    double t = now.seconds - truthAtPhase_.seconds;
    eta_.addTruth(now.rayCasts - truthAtPhase_.rayCasts, t);
    timedSeconds_ += t;
    s -= t;
    truthAtPhase_ = now;
  }
  if (phase_ == Phase::Timing) eta_.addTiming(w.scheme, w.timingFrames, s);
  if (phase_ == Phase::Measure) eta_.addMeasured(w.scheme, w.measuredFrames, s);
  if (phase_ == Phase::Timing || phase_ == Phase::Measure) timedSeconds_ += s;
  phase_ = p;
  phaseStart_ = Clock::now();
  phaseDone_ = 0;
}

void SweepProgress::frame(int done, int total) {
  phaseDone_ = done;
  bool tty = isatty(fileno(stderr));
  if (!enabled_ || done <= 0 || !(tty ? done % 10 == 0 || done == total : done % std::max(1, total / 10) == 0)) return;
  // This phase at its own rate so far; the rest of this case and the later cases at measured costs.
  const CaseWork& w = cases_[current_];
  double elapsed = since(phaseStart_);
  double left = elapsed / done * (total - done);
  CaseWork rest = w;
  rest.timingFrames = 0;
  if (phase_ != Phase::Timing) rest.measuredFrames = rest.truthFrames = 0;  // measured at the live rate
  bool caseComplete = true, restComplete = true;
  left += eta_.remaining({rest}, caseComplete) + leftAfterCurrent(restComplete);
  bool measurementUnknown = eta_.measuredCost("") < 0;
  std::fprintf(stderr, "%s    %s %d/%d  %s elapsed, %s%s", tty ? "\r" : "",
               phase_ == Phase::Measure ? "measured frame" : "frame", done, total,
               formatDuration(since(start_)).c_str(),
               leftText(left, caseComplete && restComplete, measurementUnknown).c_str(), tty ? "   " : "\n");
  std::fflush(stderr);
}

void SweepProgress::endCase(bool ok) {
  if (!ok) return;  // a failed case's parts are not the cost of a finished one
  phase(Phase::Images);
  eta_.addOverhead(cases_[current_].scheme, since(caseStart_) - timedSeconds_);
}

}  // namespace lb
