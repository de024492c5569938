#include "cli/load_bench.h"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "config/config.h"
#include "error.h"
#include "render/instanced.h"
#include "render/scheme.h"
#include "results/write.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/parallel_rows.h"
#include "terrain/terrain_cache.h"
#include "version.h"

namespace lb {
namespace {

using nlohmann::json;

// kB of a "VmHWM:" / "VmRSS:" line of /proc/self/status; -1 where there is none (not Linux).
long long procStatusKb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const size_t n = std::strlen(key);
  while (std::getline(f, line))
    if (line.compare(0, n, key) == 0) return std::atoll(line.c_str() + n);
  return -1;
}

// Writing 5 to clear_refs resets VmHWM to the current RSS (Linux >= 4.0), so each stage's peak is
// its own. Where that fails, every stage reports the peak since the process started.
bool resetPeak() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return bool(f);
}

// FNV-1a over 64-bit words (and the tail bytes): a fingerprint of a stage's output, not a
// security hash. Two runs agree bit for bit when their hashes agree.
std::string fingerprint(const void* data, size_t bytes) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint64_t h = 1469598103934665603ull;
  size_t i = 0;
  for (; i + 8 <= bytes; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = (h ^ w) * 1099511628211ull;
  }
  for (; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h));
  return s;
}

// User + system CPU seconds of the whole process: beside the wall time, it shows whether the
// stage had its threads' cores to itself (cpu / wall ~ threads) or shared them.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  auto s = [](timeval t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}

struct Stage {
  std::string name;
  double seconds = 0, cpuSeconds = 0;
  long long peakKb = -1, afterKb = -1;
  std::string hash;
};

// Times work() with its own peak RSS; hash() fingerprints the output afterwards, outside the time.
template <typename Work, typename Hash>
Stage timeStage(const std::string& name, Work work, Hash hash) {
  Stage s;
  s.name = name;
  resetPeak();
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = cpuSeconds();
  work();
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.cpuSeconds = cpuSeconds() - cpu0;
  s.peakKb = procStatusKb("VmHWM:");
  s.afterKb = procStatusKb("VmRSS:");
  s.hash = hash();
  std::fprintf(stderr, "lodbench: load-bench %-12s %8.3f s (cpu %8.3f s)  peak %7.0f MiB\n", name.c_str(), s.seconds,
               s.cpuSeconds, double(s.peakKb) / 1024.0);
  return s;
}

json stageJson(const Stage& s) {
  auto bytes = [](long long kb) { return kb >= 0 ? json(kb * 1024) : json(nullptr); };
  return {{"stage", s.name},
          {"seconds", s.seconds},
          {"cpu_seconds", s.cpuSeconds},
          {"peak_rss_bytes", bytes(s.peakKb)},
          {"rss_after_bytes", bytes(s.afterKb)},
          {"output_hash", s.hash}};
}

json specJson(const TerrainSpec& t) {
  return {{"type", t.type},
          {"file", t.file},
          {"size", t.size},
          {"seed", t.seed},
          {"extent", t.extent},
          {"height_scale", t.heightScale},
          {"detail", t.detailToSpacing ? "resolution" : "fixed"},
          {"label", terrainLabel(t)}};
}

// A scheme's load-time work: its CPU preprocessing, or for a compute scheme the CPU reference of
// its pass. Returns false when the scheme has none.
// An instanced scheme's per-terrain LOD state (trees, tables, chunked's offline meshes) is built
// with its draw path: timed here as setScheme times it, fingerprinted by its footprints.
struct SchemeOutput {
  SchemeTexture tex;
  std::unique_ptr<InstancedLod> lod;
};
bool schemeStage(const Scheme& scheme, const ParamValues& params, const Heightfield& hf, int grid, SchemeOutput& out) {
  out.tex =
      scheme.info().compute.empty() ? scheme.preprocessGrid(hf, params, grid) : scheme.computeReference(hf, params);
  // A per-sample map, made whole here (the renderer makes it page by page): the same floats.
  if (const SampleMap map = scheme.sampleMap(hf, params)) {
    std::vector<float> whole(size_t(hf.width) * size_t(hf.height));
    parallelRows(hf.height, [&](int z0, int z1) {
      for (int z = z0; z < z1; ++z) map.row(z, 0, hf.width, &whole[size_t(z) * size_t(hf.width)]);
    });
    out.tex = redTexture(hf.width, hf.height, std::move(whole));
  }
  if (scheme.info().path == DrawPath::InstancedGrid) out.lod = scheme.instancedLod(hf, params);
  return !out.tex.rgba.empty() || out.lod;
}

std::string fingerprint(const SchemeOutput& o) {
  if (o.lod) {
    uint64_t h = 1469598103934665603ull;
    for (const Footprint& f : o.lod->footprints()) {
      for (const glm::vec2& v : f.vertices) {
        uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
      for (uint32_t i : f.indices) h = (h ^ i) * 1099511628211ull;
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
  }
  if (o.tex.channels == 4) return fingerprint(o.tex.rgba.data(), o.tex.rgba.size() * sizeof(float));
  // A one-channel texture hashes as the RGBA texture (r, 0, 0, 0) it replaced, so hashes of builds
  // before and after the change compare.
  uint64_t h = 1469598103934665603ull;
  for (float r : o.tex.rgba) {
    uint32_t bits;
    std::memcpy(&bits, &r, 4);
    h = (h ^ uint64_t(bits)) * 1099511628211ull;  // little-endian word (r, 0)
    h = (h ^ 0ull) * 1099511628211ull;            // (0, 0)
  }
  char s[17];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h));
  return s;
}

void writeRaw(const std::string& file, const Heightfield& hf) {
  // Little-endian float32, row-major from sample (0, 0): what the r32f loader and an ENVI / EHdr
  // header (byte order 0) describe. x86 and ARM Linux are little-endian, so the bytes go as they are.
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) throw InputError("load-bench: cannot write " + file);
  const size_t n = std::fwrite(hf.h.data(), sizeof(float), hf.h.size(), f);
  if (std::fclose(f) != 0 || n != hf.h.size()) throw InputError("load-bench: cannot write " + file);
}

}  // namespace

int loadBenchCommand(const LoadBenchOptions& o) {
  if (o.threads > 0) setenv("LODBENCH_THREADS", std::to_string(o.threads).c_str(), 1);
  const bool perStagePeak = resetPeak();
  json out = {{"tool", "lodbench"},
              {"tool_version", kToolVersion},
              {"git_commit", gitCommit()},
              {"time", isoTimeUtc()},
              {"config_file", o.config},
              {"threads", terrainThreads()},
              {"hardware_threads", int(sysconf(_SC_NPROCESSORS_ONLN))},
              {"peak_is_per_stage", perStagePeak}};
  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  out["host"] = host;
#ifdef NDEBUG
  out["build_type"] = "release";
#else
  out["build_type"] = "debug";
#endif
  Config config;
  Stage parse = timeStage(
      "config", [&] { config = loadConfig(o.config); }, [] { return std::string(); });
  out["config"] = config.raw;
  out["grid"] = config.grid;
  json terrains = json::array();
  long long processPeakKb = parse.peakKb;
  for (size_t ti = 0; ti < config.terrains.size(); ++ti) {
    const TerrainSpec& spec = config.terrains[ti];
    std::vector<Stage> stages;
    if (ti == 0) stages.push_back(parse);
    // As a sweep gets it: a file the config stage read (and kept, when large) is not read again.
    std::shared_ptr<const Heightfield> held;
    stages.push_back(timeStage(
        "load", [&] { held = sharedHeightfield(spec); },
        [&] { return fingerprint(held->h.data(), held->h.size() * sizeof(float)); }));
    const Heightfield& hf = *held;
    if (ti == 0 && !o.writeR32f.empty()) writeRaw(o.writeR32f, hf);
    // Each output is dropped after its stage, as the renderer drops it after the upload.
    NormalMap nm;
    stages.push_back(timeStage(
        "normal_map", [&] { nm = computeNormalMap(hf); },
        [&] { return fingerprint(nm.texels.data(), nm.texels.size() * sizeof(uint16_t)); }));
    nm = NormalMap();
    for (const SchemeEntry& e : config.schemes) {
      const Scheme* scheme = findScheme(e.name);
      if (!scheme) throw InputError("load-bench: " + unknownSchemeText(e.name));
      const ParamValues params = resolveParams(scheme->info(), e.variants.empty() ? ParamValues{} : e.variants[0]);
      SchemeOutput so;
      bool any = false;
      Stage s = timeStage(
          e.name, [&] { any = schemeStage(*scheme, params, hf, config.grid, so); }, [&] { return fingerprint(so); });
      if (any) stages.push_back(s);
    }
    const double raw = 4.0 * double(hf.h.size());
    json list = json::array();
    double total = 0;
    long long peakKb = -1;
    for (const Stage& s : stages) {
      list.push_back(stageJson(s));
      total += s.seconds;
      peakKb = std::max(peakKb, s.peakKb);
    }
    processPeakKb = std::max(processPeakKb, peakKb);
    terrains.push_back({{"terrain", specJson(spec)},
                        {"width", hf.width},
                        {"height", hf.height},
                        {"raw_height_bytes", raw},
                        {"stages", list},
                        {"total_seconds", total},
                        {"peak_rss_bytes", peakKb >= 0 ? json(peakKb * 1024) : json(nullptr)},
                        {"peak_over_raw", peakKb >= 0 ? json(double(peakKb) * 1024.0 / raw) : json(nullptr)}});
  }
  out["terrains"] = terrains;
  out["peak_rss_bytes"] = processPeakKb >= 0 ? json(processPeakKb * 1024) : json(nullptr);
  const std::string text = out.dump(2) + "\n";
  std::printf("%s", text.c_str());
  if (!o.out.empty()) writeFileAtomic(o.out, text);
  return 0;
}

}  // namespace lb
