#pragma once
// What a case reports while it replays: the phase it is in and the frames done of that phase.
// The sweep's progress line (sweep/progress.h) listens; a case run alone passes none.
namespace lb {

class CaseProgress {
 public:
  enum class Phase { Setup, Timing, Measure, Images };
  virtual void phase(Phase p) = 0;              // the case enters phase p
  virtual void frame(int done, int total) = 0;  // progress within the current phase

 protected:
  ~CaseProgress() = default;
};

}  // namespace lb
