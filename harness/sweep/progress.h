#pragma once
// Progress lines and the remaining-time estimate of a sweep. The estimate comes from
// measured costs: seconds per timing frame, per measured frame and per case (set-up, images), per
// scheme once that scheme has run a case, else the mean over every case run so far; and seconds
// per ground-truth ray cast, which only the first case of a terrain, path and resolution pays (the
// truth is cached for the others: at 320x180 it was 20 s of the first case's 42). Measured
// frames (ray-cast truth, error, image metrics, surplus bisection) cost 10-100x a timing frame on
// lavapipe, so an estimate from the timing frames alone (the old one) was far too low: uniform's
// measurement passes took 63 s of its 82 s while the line said "~84 s left" for the whole sweep.
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "replay/case_progress.h"

namespace lb {

struct Config;
struct Case;

// What one case does, in the units whose costs are measured.
struct CaseWork {
  std::string scheme;
  int timingFrames = 0;    // warm-up, timed frames x repetitions, timing-mode replays
  int measuredFrames = 0;  // frames the measurement passes run on
  int truthFrames = 0;     // ground-truth ray casts it makes (not cached by an earlier case)
  bool overhead = true;    // set-up and images still to come (false once a case reaches them)
};

// Each case's work as runCase will do it (the camera path is read for its frame count).
std::vector<CaseWork> plannedWork(const Config& config, const std::vector<Case>& cases);

class EtaEstimator {
 public:
  // One finished part of a case: `units` frames (or 1 case for the overhead) took `seconds`.
  void addTiming(const std::string& scheme, int frames, double seconds);
  void addMeasured(const std::string& scheme, int frames, double seconds);
  void addOverhead(const std::string& scheme, double seconds);
  void addTruth(int rayCasts, double seconds);  // the same for every scheme
  // Seconds the work will take. `complete` is false when a part of it has no measured cost yet
  // (no case has reached measurement passes): the figure then covers only the parts that have.
  double remaining(const std::vector<CaseWork>& work, bool& complete) const;
  // Seconds per unit for a scheme: its own cost, else the mean over all schemes, else < 0.
  double timingCost(const std::string& scheme) const { return cost(timing_, scheme); }
  double measuredCost(const std::string& scheme) const { return cost(measured_, scheme); }
  double overheadCost(const std::string& scheme) const { return cost(overhead_, scheme); }
  double truthCost() const { return cost(truth_, ""); }
  // A scheme's own costs only (< 0 where it has none), as run.json's "costs" records them.
  struct Own {
    double timing = -1, measured = -1, overhead = -1;
  };
  Own own(const std::string& scheme) const;

 private:
  struct Sum {
    double seconds = 0;
    long units = 0;
  };
  using Sums = std::map<std::string, Sum>;  // "" = every scheme
  static void add(Sums& s, const std::string& scheme, long units, double seconds);
  static double cost(const Sums& s, const std::string& scheme);
  Sums timing_, measured_, overhead_, truth_;
};

// "84 s", "3 min 20 s": seconds below 100, else minutes and seconds.
std::string formatDuration(double seconds);

// The sweep's progress on stderr: a line per case with the estimate for the whole rest of the
// sweep, and in-place frame counters within a case (one line per tenth when not a terminal).
class SweepProgress : public CaseProgress {
 public:
  // truth(): ray casts made so far and their seconds (ReferenceCache), kept apart from the phases.
  struct Truth {
    int rayCasts = 0;
    double seconds = 0;
  };
  SweepProgress(bool enabled, std::vector<CaseWork> cases, std::function<Truth()> truth = {});
  void startCase(size_t index, const std::string& id);
  void phase(Phase p) override;              // the case enters phase p; the time of the previous phase is recorded
  void frame(int done, int total) override;  // progress within the current phase (timing or measurement)
  void endCase(bool ok);                     // records the overhead (only of a case that finished)
  const EtaEstimator& estimator() const { return eta_; }

 private:
  double leftAfterCurrent(bool& complete) const;
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  std::vector<CaseWork> cases_;
  EtaEstimator eta_;
  size_t current_ = 0;
  Phase phase_ = Phase::Setup;
  Clock::time_point start_, caseStart_, phaseStart_;
  double timedSeconds_ = 0;  // timing, measurement and ray-cast seconds of the current case
  std::function<Truth()> truth_;
  Truth truthAtPhase_;
  int phaseDone_ = 0;  // frames done in the current phase
};

}  // namespace lb
