#include "sweep/results.h"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "metrics/stats.h"
#include "sweep/config.h"
#include "vk/context.h"

namespace lb {

using nlohmann::json;

void writeFileAtomic(const std::string& path, const std::string& contents) {
  std::string tmp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << contents;
    f.flush();
    if (!f) throw std::runtime_error("write failed: " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " -> " + path);
}

std::string gitCommit() {
  std::string cmd = std::string("git -C '") + LODBENCH_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null";
  std::array<char, 128> buf{};
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (out.empty()) {
    const char* env = std::getenv("LODBENCH_GIT_COMMIT");  // set where the tree travels without .git
    return env && *env ? env : "unknown";
  }
  std::string dirtyCmd = std::string("git -C '") + LODBENCH_SOURCE_DIR + "' status --porcelain --untracked-files=no 2>/dev/null";
  if (FILE* p = popen(dirtyCmd.c_str(), "r")) {
    if (fgets(buf.data(), int(buf.size()), p)) out += "-dirty";
    pclose(p);
  }
  return out;
}

std::string isoTimeUtc() {
  std::time_t t = std::time(nullptr);
  char s[32];
  std::strftime(s, sizeof s, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return s;
}

json runContext(const Context& ctx, const Config& config) {
  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  return {
      {"tool", "lodbench"},
      {"tool_version", LODBENCH_VERSION},
#ifdef NDEBUG
      {"build_type", "release"},
#else
      {"build_type", "debug"},
#endif
      {"git_commit", gitCommit()},
      {"device", ctx.props.deviceName},
      {"device_id", ctx.props.deviceID},
      {"vendor_id", ctx.props.vendorID},
      {"driver", ctx.driverName},
      {"driver_info", ctx.driverInfo},
      {"driver_version", driverVersionString(ctx.props)},
      {"api_version", apiVersionString(ctx.props.apiVersion)},
      {"timestamp_period_ns", ctx.props.limits.timestampPeriod},
      {"validation", ctx.validationEnabled},
      {"host", host},
      {"time", isoTimeUtc()},
      {"config_file", config.file},
      {"config", config.raw},
  };
}

static json summaryOf(const std::vector<double>& v) {
  Summary s = summarize(v);
  return {{"median", s.median}, {"p5", s.p5}, {"p95", s.p95}, {"p99", s.p99}, {"mean", s.mean},
          {"min", s.min},       {"max", s.max}, {"stddev", s.stddev}};
}

json caseSummary(const CaseResult& r) {
  if (r.frames.empty()) return json::object();
  std::vector<double> gpu, cpu, tris, patches, tes, frags;
  for (auto& f : r.frames) {
    gpu.push_back(f.gpuMs);
    cpu.push_back(f.cpuMs);
    tris.push_back(double(f.stats.clipInvocations));
    patches.push_back(double(f.stats.tcsPatches));
    tes.push_back(double(f.stats.tesInvocations));
    frags.push_back(double(f.stats.fsInvocations));
  }
  json g = summaryOf(gpu);
  double med = g["median"].get<double>();
  return {{"frames", r.frames.size()},
          {"gpu_ms", g},
          {"cpu_ms", summaryOf(cpu)},
          {"fps_median", med > 0 ? 1000.0 / med : 0.0},
          {"fps_mean", g["mean"].get<double>() > 0 ? 1000.0 / g["mean"].get<double>() : 0.0},
          {"triangles", summaryOf(tris)},
          {"patches", summaryOf(patches)},
          {"tes_invocations", summaryOf(tes)},
          {"fragment_invocations", summaryOf(frags)}};
}

json caseJson(const Case& c, const CaseResult& r) {
  json frames = json::array();
  for (auto& f : r.frames)
    frames.push_back({{"frame", f.frame},
                      {"gpu_ms", f.gpuMs},
                      {"cpu_ms", f.cpuMs},
                      {"fps", f.gpuMs > 0 ? 1000.0 / f.gpuMs : 0.0},
                      {"ia_vertices", f.stats.iaVertices},
                      {"ia_primitives", f.stats.iaPrimitives},
                      {"vs_invocations", f.stats.vsInvocations},
                      {"patches", f.stats.tcsPatches},
                      {"tes_invocations", f.stats.tesInvocations},
                      {"clip_invocations", f.stats.clipInvocations},
                      {"clip_primitives", f.stats.clipPrimitives},
                      {"fragment_invocations", f.stats.fsInvocations}});
  json params = json::object();
  for (auto& [k, v] : c.params) params[k] = v;
  return {{"schema_version", kSchemaVersion},
          {"case_id", c.id},
          {"scheme", c.scheme},
          {"params", params},
          {"terrain", {{"type", c.terrain.type}, {"label", c.terrainLabel}, {"file", c.terrain.file},
                       {"size", c.terrain.size}, {"seed", c.terrain.seed}, {"extent", c.terrain.extent},
                       {"height_scale", c.terrain.heightScale}}},
          {"path", c.path},
          {"resolution", {c.width, c.height}},
          {"status", r.status},
          {"reason", r.reason},
          {"seconds", r.seconds},
          {"images", r.images},
          {"summary", caseSummary(r)},
          {"frames", frames}};
}

std::string framesCsvHeader() {
  return "case_id,frame,gpu_ms,cpu_ms,patches,tes_invocations,clip_invocations,clip_primitives,fragment_invocations\n";
}

std::string framesCsvRows(const std::string& caseId, const CaseResult& r) {
  std::ostringstream s;
  s.precision(9);
  for (auto& f : r.frames)
    s << caseId << ',' << f.frame << ',' << f.gpuMs << ',' << f.cpuMs << ',' << f.stats.tcsPatches << ','
      << f.stats.tesInvocations << ',' << f.stats.clipInvocations << ',' << f.stats.clipPrimitives << ','
      << f.stats.fsInvocations << '\n';
  return s.str();
}

}  // namespace lb
