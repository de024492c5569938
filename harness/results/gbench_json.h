#pragma once
// A finished run in Google Benchmark's JSON schema (docs/design.md, Output), so that its tools read
// lodbench results: /usr/share/benchmark/compare.py benchmarks <run-a>/gbench.json <run-b>/gbench.json.
// One benchmark per case (name = case_id): real_time = median GPU time, cpu_time = median CPU time,
// both in microseconds (time_unit "us": compare.py prints whole units, and frames last under 1 ms),
// iterations = timing frames, counters (triangles, patches, err_mean_px, ...) as plain fields. With
// config repetitions > 1 the frames are split into one entry per repetition plus mean / median /
// stddev aggregates, as Google Benchmark writes them (compare.py's U test needs >= 2 repetitions).
// A failed or skipped case is an entry with error_occurred and its reason.
#include <nlohmann/json.hpp>
#include <string>

namespace lb {

// Builds the document from <runDir>/run.json and <runDir>/cases/*.json. Throws InputError naming
// the file when one is missing or not JSON.
nlohmann::json googleBenchmarkJson(const std::string& runDir);
// Writes <runDir>/gbench.json atomically and returns its path.
std::string writeGoogleBenchmarkJson(const std::string& runDir);

}  // namespace lb
