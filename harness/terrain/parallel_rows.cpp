#include "terrain/parallel_rows.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <thread>
#include <vector>

namespace lb {

int terrainThreads() {
  if (const char* env = std::getenv("LODBENCH_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && n > 0) return int(std::min(n, 1024L));
  }
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

void parallelRows(int rows, const std::function<void(int, int)>& body, int minRowsPerBand) {
  if (rows <= 0) return;
  const int bands = std::max(1, std::min(terrainThreads(), rows / std::max(1, minRowsPerBand)));
  if (bands == 1) {
    body(0, rows);
    return;
  }
  // An exception in a worker is kept and rethrown here after every thread has joined.
  std::vector<std::exception_ptr> errors(static_cast<size_t>(bands));
  auto run = [&](int b) {
    try {
      body(int(int64_t(rows) * b / bands), int(int64_t(rows) * (b + 1) / bands));
    } catch (...) {
      errors[size_t(b)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(size_t(bands - 1));
  for (int b = 1; b < bands; ++b) pool.emplace_back(run, b);
  run(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace lb
