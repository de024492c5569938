#pragma once
// Hand-made run directories (docs/results-format.md) for tests of compare and gbench.json:
// every figure is chosen here, so expectations follow from the inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lb::test {

using nlohmann::json;

inline json runContext(const std::string& device = "llvmpipe (LLVM 15.0.6, 256 bits)",
                       const std::string& driverInfo = "Mesa 22.3.6 (LLVM 15.0.6)") {
  return {{"tool", "lodbench"},
          {"device", device},
          {"driver", "llvmpipe"},
          {"driver_info", driverInfo},
          {"git_commit", "abc123"},
          {"host", "testhost"},
          {"time", "2026-11-21T20:00:00Z"},
          {"build_type", "release"},
          {"config", {{"repetitions", 1}}}};
}

// One timing frame: counters derived from the frame index, so equal inputs give equal counters.
inline json frameRecord(int frame, double gpuMs) {
  return {{"frame", frame},
          {"gpu_ms", gpuMs},
          {"cpu_ms", 2.0 * gpuMs},
          {"patches", 64},
          {"tes_invocations", 1000 + frame},
          {"clip_invocations", 2000 + 2 * frame},
          {"clip_primitives", 1900 + 2 * frame},
          {"fragment_invocations", 30000 + frame}};
}

// gpu ms of frame i: base * (1 + 0.02 * ((7 i) mod 11) / 10): a deterministic 2% spread.
inline std::vector<double> gpuTimes(int frames, double base) {
  std::vector<double> v;
  for (int i = 0; i < frames; ++i) v.push_back(base * (1.0 + 0.02 * double((7 * i) % 11) / 10.0));
  return v;
}

inline json caseDoc(const std::string& id, const std::vector<double>& gpu, const std::string& status = "ok") {
  json frames = json::array();
  for (size_t i = 0; i < gpu.size(); ++i) frames.push_back(frameRecord(int(i), gpu[i]));
  return {{"schema_version", 1},
          {"case_id", id},
          {"scheme", "uniform"},
          {"status", status},
          {"reason", status == "ok" ? "" : "device lost"},
          {"summary", json::object()},
          {"frames", frames}};
}

inline void writeText(const std::string& file, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(file).parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

// A fresh directory under the test temp dir holding run.json and cases/<id>.json.
inline std::string writeRun(const std::string& name, const json& context, const std::vector<json>& cases) {
  std::string dir = ::testing::TempDir() + "/lodbench_synthetic/" + name;
  std::filesystem::remove_all(dir);
  writeText(dir + "/run.json", json{{"schema_version", 1}, {"context", context}}.dump(1));
  for (auto& c : cases) writeText(dir + "/cases/" + c["case_id"].get<std::string>() + ".json", c.dump(1));
  return dir;
}

}  // namespace lb::test
