// Merging shards that a cluster scheduler retried: a folder named twice, a shard
// re-run into a second folder, a failed attempt beside its retry, and two finished copies of a
// case that differ. The output must depend only on the set of folders (every file compared byte
// for byte), and differing finished copies must be refused, naming the case and both folders.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "cli_run.h"
#include "error.h"
#include "sweep/merge.h"
#include "synthetic_run.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Lexically normal: merge names folders so (TempDir() ends in a slash). One folder per test: ctest
// runs tests in parallel processes, and a shared one had one test remove another's shards.
std::string root() {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  return fs::path(::testing::TempDir() + "/lodbench_merge_" + test).lexically_normal().string();
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A shard folder as `run` leaves it: run.json with shard, times and the board, case files, and
// one image per case that the case file lists.
struct Shard {
  std::string name;
  int index = 0, count = 2;
  std::string start = "2026-11-21T20:00:00Z", end = "2026-11-21T20:05:00Z", host = "node-a";
  std::string uuid = "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f";
  std::vector<json> cases;
};

json shardCase(const std::string& id, double gpuMs, const std::string& status = "ok") {
  json c = test::caseDoc(id, test::gpuTimes(6, gpuMs), status);
  c["digest"] = "digest-of-" + id;
  c["seconds"] = 1.25;
  c["images"] = json::array({"images/" + id + "_f0_shaded.png"});
  return c;
}

std::string writeShard(const Shard& s) {
  std::string dir = root() + "/" + s.name;
  fs::remove_all(dir);
  json ctx = test::runContext();
  ctx["tool_version"] = "0.4.0";
  ctx["host"] = s.host;
  ctx["time"] = s.start;
  ctx["device_uuid"] = s.uuid;
  ctx["power_limit_w"] = nullptr;
  ctx["power_limit_reason"] = "not an NVIDIA device (vendor 0x10005): NVML reads NVIDIA boards only";
  json run = {{"schema_version", 1},
              {"context", ctx},
              {"start_time", s.start},
              {"end_time", s.end},
              {"shard", {{"index", s.index}, {"count", s.count}}}};
  test::writeText(dir + "/run.json", run.dump(2));
  for (auto& c : s.cases) {
    std::string id = c["case_id"];
    test::writeText(dir + "/cases/" + id + ".json", c.dump(2));
    // The image's bytes follow from the case's first GPU time: equal cases, equal images.
    test::writeText(dir + "/images/" + id + "_f0_shaded.png", "PNG of " + id + " " + c["frames"][0]["gpu_ms"].dump());
  }
  return dir;
}

// Every file under dir, relative path -> bytes.
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = bytesOf(e.path());
  return files;
}

// Merges into a fresh `out` and returns every file it wrote.
std::map<std::string, std::string> mergeInto(const std::string& out, const std::vector<std::string>& dirs,
                                             MergeTotals* totals = nullptr) {
  fs::remove_all(out);
  MergeTotals t = mergeRuns(out, dirs, false);
  if (totals) *totals = t;
  return snapshot(out);
}

std::string fileNames(const std::map<std::string, std::string>& files) {
  std::string s;
  for (auto& [k, v] : files) s += k + " ";
  return s;
}

Shard shard0() {
  Shard s{"s0", 0};
  s.cases = {shardCase("a", 1.0), shardCase("c", 3.0)};
  return s;
}

Shard shard1() {
  Shard s{"s1", 1};
  s.cases = {shardCase("b", 2.0), shardCase("d", 4.0)};
  s.host = "node-b";
  s.uuid = "0f1e2d3c-4b5a-6978-8796-a5b4c3d2e1f0";  // another board of the model
  s.start = "2026-11-21T20:00:30Z";
  s.end = "2026-11-21T20:06:00Z";
  return s;
}

}  // namespace

TEST(Merge, AFolderNamedTwiceOrInAnyOrderGivesTheSameBytes) {
  std::string s0 = writeShard(shard0()), s1 = writeShard(shard1()), out = root() + "/out";
  MergeTotals t;
  auto once = mergeInto(out, {s0, s1}, &t);
  EXPECT_EQ(t.cases, 4);
  EXPECT_EQ(t.duplicates, 0);
  EXPECT_EQ(t.folders, 2);
  for (const char* f : {"run.json", "summary.json", "frames.csv", "gbench.json", "cases/a.json", "cases/d.json",
                        "images/a_f0_shaded.png", "images/d_f0_shaded.png"})
    EXPECT_TRUE(once.count(f)) << f << " missing; have " << fileNames(once);
  EXPECT_EQ(once.size(), 4u + 4u + 4u) << fileNames(once);

  // Merging again: no time of the merge, no load average, nothing of the order.
  EXPECT_EQ(mergeInto(out, {s0, s1}), once) << "the same merge twice";
  EXPECT_EQ(mergeInto(out, {s1, s0}), once) << "reversed";
  auto twice = mergeInto(out, {s0, s1, s0, s0 + "/", root() + "/./s1"}, &t);
  EXPECT_EQ(twice, once) << "a folder named twice, in other spellings";
  EXPECT_EQ(t.folders, 2);
  EXPECT_EQ(t.duplicates, 0) << "one folder named twice holds each case once";
  EXPECT_EQ(t.cases, 4);

  json run = json::parse(once["run.json"]);
  EXPECT_EQ(run["merged_from"], json::array({s0, s1}));
  EXPECT_EQ(run["case_ids"], json::array({"a", "b", "c", "d"}));
  EXPECT_EQ(run["start_time"], "2026-11-21T20:00:00Z") << "the earliest start";
  EXPECT_EQ(run["end_time"], "2026-11-21T20:06:00Z") << "the latest end, not the merge's time";
  EXPECT_EQ(run["context"]["host"], "node-a") << "the context of the folder started first";
  // Each folder's board, with the cases taken from it.
  ASSERT_EQ(run["merged_inputs"].size(), 2u);
  EXPECT_EQ(run["merged_inputs"][1]["device_uuid"], "0f1e2d3c-4b5a-6978-8796-a5b4c3d2e1f0");
  EXPECT_EQ(run["merged_inputs"][1]["host"], "node-b");
  EXPECT_EQ(run["merged_inputs"][1]["case_ids"], json::array({"b", "d"}));
  EXPECT_EQ(run["merged_inputs"][0]["shard"]["index"], 0);
  json gbench = json::parse(once["gbench.json"]);
  EXPECT_FALSE(gbench["context"].contains("load_avg")) << "the merging machine's load is no fact of the run";
  EXPECT_EQ(gbench["context"]["device_uuid"], "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f");
}

// Kubernetes re-runs shard 0 with the same index into another folder (or the fan-in copies its
// output twice): the same case files and images, another run.json (started later, elsewhere).
TEST(Merge, AShardReRunWithTheSameCasesChangesNoCaseOrAggregate) {
  std::string s0 = writeShard(shard0()), s1 = writeShard(shard1()), out = root() + "/out_rerun";
  Shard retry = shard0();
  retry.name = "s0-retry";
  retry.start = "2026-11-21T21:00:00Z";
  retry.end = "2026-11-21T21:05:00Z";
  retry.host = "node-c";
  retry.uuid = "11111111-2222-3333-4444-555555555555";
  std::string r0 = writeShard(retry);

  auto plain = mergeInto(out, {s0, s1});
  MergeTotals t;
  auto withRetry = mergeInto(out, {r0, s1, s0}, &t);
  EXPECT_EQ(t.cases, 4);
  EXPECT_EQ(t.duplicates, 2) << "a and c twice";
  EXPECT_TRUE(t.notes.empty()) << "byte-identical copies need no remark";
  ASSERT_EQ(withRetry.size(), plain.size()) << fileNames(withRetry);
  for (auto& [file, bytes] : plain)
    if (file != "run.json") EXPECT_EQ(withRetry[file], bytes) << file << " differs with the retried shard";
  json run = json::parse(withRetry["run.json"]), was = json::parse(plain["run.json"]);
  EXPECT_EQ(run["context"], was["context"]) << "the attempt started first keeps the context";
  EXPECT_EQ(run["case_ids"], was["case_ids"]);
  EXPECT_EQ(run["merged_from"], json::array({s0, r0, s1}));
  // Whichever order: the same bytes, run.json too.
  EXPECT_EQ(mergeInto(out, {s0, r0, s1, r0}), withRetry);
  EXPECT_EQ(mergeInto(out, {s1, s0, r0}), withRetry);
}

// The attempt that failed left a failed case; the retry finished it. The finished copy is kept,
// whichever folder comes first, and the choice is named on stderr (notes).
TEST(Merge, AFinishedCopySupersedesAFailedAttempt) {
  Shard failed = shard0();
  failed.name = "s0-attempt1";
  failed.cases = {shardCase("a", 9.0, "failed"), shardCase("c", 3.0)};
  std::string f0 = writeShard(failed), s0 = writeShard(shard0()), s1 = writeShard(shard1());
  std::string out = root() + "/out_failed";
  MergeTotals t;
  auto files = mergeInto(out, {f0, s0, s1}, &t);
  json a = json::parse(files["cases/a.json"]);
  EXPECT_EQ(a["status"], "ok");
  EXPECT_EQ(files["images/a_f0_shaded.png"], bytesOf(s0 + "/images/a_f0_shaded.png")) << "the kept copy's image";
  ASSERT_EQ(t.notes.size(), 1u);
  EXPECT_NE(t.notes[0].find("case a: kept the finished copy in " + s0 + " over the failed copy in " + f0),
            std::string::npos)
      << t.notes[0];
  EXPECT_EQ(mergeInto(out, {s1, s0, f0}), files);
  // Two unfinished copies that differ: the first folder's by name, said on stderr.
  Shard failedToo = failed;
  failedToo.name = "s0-attempt2";
  failedToo.cases = {shardCase("a", 8.0, "failed")};
  std::string f1 = writeShard(failedToo);
  auto unfinished = mergeInto(out, {f1, f0}, &t);
  EXPECT_EQ(json::parse(unfinished["cases/a.json"])["frames"][0]["gpu_ms"], 9.0) << "s0-attempt1 sorts first";
  EXPECT_EQ(mergeInto(out, {f0, f1}), unfinished);
}

// Two finished copies of one case that differ (the case measured twice: other timings) are
// refused, force or not, naming the case and both folders; nothing is written.
TEST(Merge, TwoFinishedCopiesThatDifferAreRefusedNamingBoth) {
  std::string s0 = writeShard(shard0()), s1 = writeShard(shard1());
  Shard remeasured = shard0();
  remeasured.name = "s0-remeasured";
  remeasured.cases[1] = shardCase("c", 3.1);  // c measured again: other GPU times
  std::string r0 = writeShard(remeasured), out = root() + "/out_conflict";
  fs::remove_all(out);
  for (bool force : {false, true}) {
    try {
      mergeRuns(out, {s1, r0, s0}, force);
      ADD_FAILURE() << "merged two differing copies of case c (force " << force << ")";
    } catch (const InputError& e) {
      std::string m = e.what();
      EXPECT_NE(m.find("case c: " + s0 + "/cases/c.json and " + r0 + "/cases/c.json differ"), std::string::npos) << m;
      EXPECT_NE(m.find("frames[].gpu_ms"), std::string::npos) << "says what differs: " << m;
      EXPECT_EQ(m.find("case a"), std::string::npos) << "a is the same in both: " << m;
    }
    EXPECT_FALSE(fs::exists(out)) << "refused before writing anything";
  }

  // Identical case files whose images differ are two different copies as well.
  Shard otherImage = shard0();
  otherImage.name = "s0-other-image";
  std::string i0 = writeShard(otherImage);
  test::writeText(i0 + "/images/a_f0_shaded.png", "another PNG");
  try {
    mergeRuns(out, {s0, i0}, false);
    ADD_FAILURE() << "merged copies of case a whose images differ";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("case a: " + s0 + "/cases/a.json and " + i0 +
                                         "/cases/a.json differ (image images/a_f0_shaded.png)"),
              std::string::npos)
        << e.what();
  }

  // The command: exit 2, both folders named.
  test::CliOut o = test::lodbench("merge --out " + out + " " + s0 + " " + r0 + " " + s1);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("case c: " + s0 + "/cases/c.json and " + r0 + "/cases/c.json differ"), std::string::npos)
      << o.text;
  o = test::lodbench("merge --help");
  EXPECT_NE(o.text.find("byte-identical"), std::string::npos) << o.text;
}

// A folder merged into before: case files this merge did not write stay on disk but out of the
// run (stale_cases), so the aggregates equal a merge into a fresh folder. --out may not be an input.
TEST(Merge, AnEarlierMergesCasesInTheOutputFolderAreStale) {
  std::string s0 = writeShard(shard0()), s1 = writeShard(shard1()), out = root() + "/out_again";
  mergeInto(out, {s0, s1});
  mergeRuns(out, {s1}, false);
  auto again = snapshot(out);
  auto fresh = mergeInto(root() + "/out_fresh", {s1});
  json run = json::parse(again["run.json"]);
  EXPECT_EQ(run["stale_cases"], json::array({"a", "c"}));
  EXPECT_EQ(run["case_ids"], json::array({"b", "d"}));
  for (const char* f : {"summary.json", "frames.csv", "cases/b.json"}) EXPECT_EQ(again[f], fresh[f]) << f;
  EXPECT_THROW(mergeRuns(s0, {s0, s1}, false), InputError);
}
