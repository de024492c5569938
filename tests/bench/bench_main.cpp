// lodbench_bench: microbenchmarks (tests/bench/). Not a test: timings are not pass/fail. Run
//   build/lodbench_bench --benchmark_out=bench.json --benchmark_out_format=json
// and compare two such files with /usr/share/benchmark/compare.py benchmarks a.json b.json.
#include <functional>
#include <string>
#include <vector>

#include "bench.h"
#include "schemes/registry.h"
#include "version.h"

namespace {

struct Entry {
  std::string name;  // BM_<What>/<param>
  std::function<void(benchmark::State&)> run;
};

std::vector<Entry> table() {
  using namespace lb;
  const std::string paths = std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/";
  std::vector<Entry> t = {
      {"BM_DensityMap/129", [](auto& s) { benchDensityMap(s, 129); }},
      {"BM_DensityMap/513", [](auto& s) { benchDensityMap(s, 513); }},
      {"BM_PlaneFit/book/513", [](auto& s) { benchPlaneFit(s, 513, true); }},
      {"BM_PlaneFit/lsq/513", [](auto& s) { benchPlaneFit(s, 513, false); }},
      {"BM_TessDeviation/1025", [](auto& s) { benchTessDeviation(s, 1025, false); }},
      {"BM_TessDeviationReference/1025", [](auto& s) { benchTessDeviation(s, 1025, true); }},
      {"BM_SamplePose/flyover", [paths](auto& s) { benchSamplePose(s, paths + "flyover.csv"); }},
      {"BM_SamplePose/lowalt", [paths](auto& s) { benchSamplePose(s, paths + "lowalt.csv"); }},
      {"BM_StatsSummarize/300", [](auto& s) { benchSummarize(s, 300); }},
      {"BM_StatsSummarize/10000", [](auto& s) { benchSummarize(s, 10000); }},
      {"BM_StatsPercentile/10000", [](auto& s) { benchPercentile(s, 10000); }},
      {"BM_StatsMannWhitney/300", [](auto& s) { benchMannWhitney(s, 300); }},
      {"BM_StatsBootstrap/300", [](auto& s) { benchBootstrap(s, 300); }},
      {"BM_CompareImages/320x180", [](auto& s) { benchCompareImages(s, 320, 180); }},
      {"BM_Ssim/320x180", [](auto& s) { benchSsim(s, 320, 180); }},
      {"BM_GpuReduce1080p", [](auto& s) { benchGpuReduce(s, 1920, 1080); }},
      {"BM_CpuReduce1080p", [](auto& s) { benchCpuReduce(s, 1920, 1080); }},
      {"BM_WriteCase/300", [](auto& s) { benchWriteCase(s, 300); }},
      {"BM_GpuRaycast1080p", [](auto& s) { benchGpuRaycast(s, 1920, 1080); }},
      {"BM_CpuRaycast1080p", [](auto& s) { benchCpuRaycast(s, 1920, 1080); }},
      {"BM_CbtUpdate/d25", [](auto& s) { benchCbtUpdate(s); }},
      {"BM_CbtStateAside/d25/host", [](auto& s) { benchCbtStateAside(s, false); }},
      {"BM_CbtStateAside/d25/device", [](auto& s) { benchCbtStateAside(s, true); }},
      {"BM_CbtErrorMap1080p", [](auto& s) { benchCbtErrorMap(s); }},
      {"BM_HostRead/8MiB/storage", [](auto& s) { benchHostRead(s, 8u << 20, false); }},
      {"BM_HostRead/8MiB/readback", [](auto& s) { benchHostRead(s, 8u << 20, true); }},
  };
  // Every scheme in the registry: a new scheme gets its benchmark without an edit here.
  for (const Scheme* scheme : allSchemes())
    t.push_back({"BM_SchemeUpdate/" + scheme->info().name, [scheme](auto& s) { benchSchemeUpdate(s, *scheme); }});
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  for (auto& e : table()) benchmark::RegisterBenchmark(e.name.c_str(), e.run);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("lodbench_version", lb::kToolVersion);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
