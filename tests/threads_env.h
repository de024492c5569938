#pragma once
// LODBENCH_THREADS (the terrain passes' thread count, terrain/parallel_rows.h) set for a scope and
// restored after it, so a test of "the same bits on any number of threads" leaves the next test
// the environment it found.
#include <cstdlib>
#include <string>

namespace lb {

class ThreadsEnv {
 public:
  explicit ThreadsEnv(int n) {
    const char* v = std::getenv("LODBENCH_THREADS");
    had_ = v != nullptr;
    if (had_) old_ = v;
    set(n);
  }
  ThreadsEnv(const ThreadsEnv&) = delete;
  ThreadsEnv& operator=(const ThreadsEnv&) = delete;
  ~ThreadsEnv() {
    if (had_)
      setenv("LODBENCH_THREADS", old_.c_str(), 1);
    else
      unsetenv("LODBENCH_THREADS");
  }
  void set(int n) { setenv("LODBENCH_THREADS", std::to_string(n).c_str(), 1); }

 private:
  std::string old_;
  bool had_ = false;
};

}  // namespace lb
