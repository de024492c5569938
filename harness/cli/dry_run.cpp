#include "cli/dry_run.h"

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "error.h"
#include "results/run_dir.h"
#include "sweep/progress.h"
#include "sweep/runner.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

// Bytes of a run folder, images aside, per frame record, for a config no earlier run can size: the
// committed CI baseline (results/baseline/ci/r1: 14 cases, 280 frame records, measured on 1 frame
// in 10; case files, frames.csv, summary.json, gbench.json, run.json) holds 474,090 bytes, 1,693
// per record. Images are bounded by their raw RGB size. Both are printed as such, never as a
// measurement of this config.
constexpr double kBytesPerFrameRecord = 1693;

namespace {

struct Earlier {
  std::string dir;
  json run;
  double bytesPerFrame = -1, bytesPerImage = -1;  // < 0: the folder cannot say
};

double bytesUnder(const fs::path& dir, int* files = nullptr) {
  double total = 0;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  for (auto& e : fs::recursive_directory_iterator(dir, ec))
    if (e.is_regular_file(ec)) {
      total += double(e.file_size(ec));
      if (files) ++*files;
    }
  return total;
}

// The newest run folder beside outDir (or in results/<name>/) whose run.json ended with costs.
Earlier newestEarlierRun(const Config& config, const std::string& outDir) {
  fs::path folder =
      outDir.empty() ? fs::path("results") / config.name : fs::path(outDir).lexically_normal().parent_path();
  Earlier best;
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec)) return best;
  std::string bestEnd;
  for (auto& e : fs::directory_iterator(folder, ec)) {
    if (e.is_symlink(ec) || !e.is_directory(ec) || !hasRunJson(e.path().string())) continue;  // skip `latest`
    json rj;
    try {
      rj = readRunJson(e.path().string());
    } catch (const InputError&) {
      continue;  // not a run of ours: nothing to estimate from
    }
    if (!rj.contains("costs") || !rj["costs"].is_object() || !rj.contains("end_time")) continue;
    std::string end = rj["end_time"].is_string() ? rj["end_time"].get<std::string>() : "";
    if (end > bestEnd) {
      bestEnd = end;
      best = {e.path().string(), rj};
    }
  }
  if (best.dir.empty()) return best;
  long frames = 0;
  for (auto& cf : readCaseFiles(best.dir)) frames += long(cf.doc["frames"].size());
  int images = 0;
  double imageBytes = bytesUnder(fs::path(best.dir) / "images", &images);
  // Everything `run` wrote but the images (case files, frames.csv, summaries, the truth cache)
  // grows with the records; a report made later is not the run's.
  const double report = bytesUnder(fs::path(best.dir) / "report");
  if (frames > 0) best.bytesPerFrame = (bytesUnder(best.dir) - imageBytes - report) / double(frames);
  if (images > 0) best.bytesPerImage = imageBytes / images;
  return best;
}

std::string byteText(double bytes) {
  char b[32];
  if (bytes < 1e6)
    std::snprintf(b, sizeof b, "%.1f kB", bytes / 1e3);
  else if (bytes < 1e9)
    std::snprintf(b, sizeof b, "%.1f MB", bytes / 1e6);
  else
    std::snprintf(b, sizeof b, "%.2f GB", bytes / 1e9);
  return b;
}

}  // namespace

int dryRun(const Config& config, const std::string& outDir, int shardIndex, int shardCount, bool shardGiven) {
  auto cases = shardCases(config, shardIndex, shardCount);
  // What a resume of --out would keep, planned first: a case recorded under another listing of
  // the same parameters keeps that id (planResume), and the ids printed are those the run uses.
  const bool resume = !outDir.empty() && hasRunJson(outDir);
  ResumePlan plan;
  if (resume) {
    checkToolVersion(outDir, readRunJson(outDir));
    plan = planResume(outDir, cases);
  }
  for (auto& c : cases) std::printf("%s\n", c.id.c_str());
  std::fflush(stdout);  // the ids first, then the totals on stderr, also through a pipe
  if (!shardGiven)      // no shard asked: nothing to say about shards
    std::fprintf(stderr, "lodbench: %zu cases\n", cases.size());
  else
    std::fprintf(stderr, "lodbench: %zu cases (shard %d/%d of %zu)\n", cases.size(), shardIndex, shardCount,
                 expandCases(config).size());
  std::vector<CaseWork> work = plannedWork(config, cases);
  if (resume) {
    std::fprintf(stderr,
                 "lodbench: %s exists: %zu finished case(s) kept, %zu changed (refused without --rerun-changed), "
                 "%zu stale, %zu to run\n",
                 outDir.c_str(), plan.reuse.size(), plan.changed.size(), plan.stale.size(),
                 cases.size() - plan.reuse.size());
    for (size_t i = 0; i < cases.size(); ++i)
      if (plan.reuse.count(cases[i].id)) work[i] = CaseWork{cases[i].scheme, 0, 0, 0, false};
  }
  // Records: the timed frames of each repetition (plannedWork's timing frames less warm-up, per
  // timing mode). Images: the configured frames and up to 4 worst ones (summary worst_frames) per mode.
  long frames = 0, images = 0;
  int modes = 1;
  for (const std::string& m : config.timing.modes) modes += m != "shaded";
  const long perCaseImages =
      long(config.images.frames.size() + (config.images.worst && config.measure.every > 0 ? 4 : 0)) *
      long(config.images.modes.size());
  for (auto& w : work) {
    if (!w.overhead) continue;  // kept
    frames += w.timingFrames / modes - config.warmupFrames;
    images += perCaseImages;
  }
  Earlier earlier = newestEarlierRun(config, outDir);
  if (earlier.dir.empty()) {
    std::fprintf(stderr,
                 "lodbench: estimated time: no estimate (no earlier run of '%s' with costs in its results folder; "
                 "the first run records them in run.json \"costs\")\n",
                 config.name.c_str());
  } else {
    EtaEstimator eta;
    for (auto& item : earlier.run["costs"].items()) {
      // Plain names, not a structured binding: clang before 16 (the fuzz build) cannot capture one.
      const std::string scheme = item.key();
      const nlohmann::json& cost = item.value();
      if (scheme == "terrains" || !cost.is_object()) continue;
      auto add = [&](const char* key, auto fn) {
        if (cost.contains(key) && cost[key].is_number()) fn(cost[key].get<double>());
      };
      add("timing_s_per_frame", [&](double s) { eta.addTiming(scheme, 1, s); });
      add("measured_s_per_frame", [&](double s) { eta.addMeasured(scheme, 1, s); });
      add("case_overhead_s", [&](double s) { eta.addOverhead(scheme, s); });
    }
    if (earlier.run.contains("ray_cast_s_per_image") && earlier.run["ray_cast_s_per_image"].is_number())
      eta.addTruth(1, earlier.run["ray_cast_s_per_image"].get<double>());
    bool complete = true;
    double s = eta.remaining(work, complete);
    std::fprintf(stderr,
                 "lodbench: estimated time: %s%s (from the costs of %s: per scheme, else their mean; they scale "
                 "with resolution, grid and device)\n",
                 complete ? "about " : "at least ", formatDuration(s).c_str(), earlier.dir.c_str());
  }
  const bool measured = earlier.bytesPerFrame > 0, imaged = earlier.bytesPerImage > 0;
  const double recordBytes = double(frames) * (measured ? earlier.bytesPerFrame : kBytesPerFrameRecord);
  const double imageBytes =
      double(images) * (imaged ? earlier.bytesPerImage : double(config.images.width) * config.images.height * 3);
  const std::string perRecord =
      measured ? "the bytes per record of " + earlier.dir : std::string("about 1.7 kB each, the CI baseline's");
  const std::string perImage =
      imaged ? "the mean image size of " + earlier.dir : std::string("their raw RGB size, an upper bound");
  // Worst frames often coincide with configured ones or each other: the image count is a ceiling.
  std::fprintf(
      stderr,
      "lodbench: estimated disk: about %s of records and summaries (%ld frame records at %s) and at most %s of images "
      "(up to %ld: configured and worst frames x modes, at %s)\n",
      byteText(recordBytes).c_str(), frames, perRecord.c_str(), byteText(imageBytes).c_str(), images, perImage.c_str());
  return 0;
}

}  // namespace lb
