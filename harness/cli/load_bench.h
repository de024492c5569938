#pragma once
// `lodbench load-bench CONFIG`: what loading a terrain costs before the first frame, stage by
// stage, on the CPU: parsing the config (which reads file terrains once to check them), the
// terrain load, the normal map, and each configured scheme's preprocessing (Scheme::preprocessGrid;
// for a pre-pass that runs as a GPU compute shader its CPU reference, Scheme::computeReference,
// stands in). Per stage: wall seconds, peak resident memory
// during the stage and a hash of its output (so runs with different thread counts or builds can
// be checked for identical results). Writes JSON to stdout (and --out).
#include <string>

namespace lb {

struct LoadBenchOptions {
  std::string config;
  std::string out;        // "" = stdout only
  int threads = 0;        // 0 = all hardware threads; else sets LODBENCH_THREADS for the passes
  std::string writeR32f;  // write the first terrain's heights here (raw little-endian float32)
};

int loadBenchCommand(const LoadBenchOptions& options);

}  // namespace lb
