#include "compare/suite_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "compare/run_data.h"
#include "compare/significance.h"
#include "results/write.h"

namespace lb {
namespace {

// The log of each repetition's mean GPU ms over its frames.
std::vector<double> logRepMeans(const SchemeTimings& s) {
  std::vector<double> out;
  for (const auto& rep : s.reps) {
    double t = 0;
    for (double v : rep) t += v;
    out.push_back(std::log(t / double(rep.size())));
  }
  return out;
}

struct LogStats {
  double mean = 0, var = 0;  // sample variance (n - 1)
  size_t n = 0;
};

LogStats logStats(const std::vector<double>& x) {
  LogStats st;
  st.n = x.size();
  for (double v : x) st.mean += v / double(x.size());
  for (double v : x) st.var += x.size() > 1 ? (v - st.mean) * (v - st.mean) / double(x.size() - 1) : 0.0;
  return st;
}

// A log-scale difference with Welch-Satterthwaite pieces: sum of variance components v_i, each
// with df_i, for a t interval; df = (sum v)^2 / sum(v^2 / df).
struct LogDiff {
  double value = 0;
  double var = 0, dfDenominator = 0;
  bool interval = true;
  void add(const LogStats& s, double weight) {
    if (s.n < 2) {
      interval = false;
      return;
    }
    const double v = weight * weight * s.var / double(s.n);
    var += v;
    dfDenominator += v * v / double(s.n - 1);
  }
  Interval at(double confidence) const {
    const double point = std::exp(value);
    if (!interval) return {point, std::nan(""), std::nan("")};
    if (var <= 0) return {point, point, point};  // identical repetitions: no spread at all
    const double df = var * var / dfDenominator;
    const double half = studentQuantile(confidence, df) * std::sqrt(var);
    return {point, std::exp(value - half), std::exp(value + half)};
  }
};

size_t checkFrames(const Workload& w) {
  size_t frames = 0;
  for (const SchemeTimings& s : w.schemes)
    for (const auto& r : s.reps) {
      if (r.size() != s.reps.front().size())
        throw std::invalid_argument("suiteVerdict: " + w.id + ", " + s.scheme + ": repetitions of different lengths");
      if (frames != 0 && r.size() != frames)
        throw std::invalid_argument("suiteVerdict: " + w.id + ": schemes timed over different frame counts");
      frames = r.size();
    }
  return frames;
}

}  // namespace

SuiteVerdict suiteVerdict(const std::vector<Workload>& workloads, double confidence, double margin) {
  SuiteVerdict v;
  v.confidence = confidence;
  v.margin = margin;
  std::map<std::string, SchemeResult> schemes;
  std::map<std::string, std::vector<std::pair<LogStats, LogStats>>> pieces;  // scheme -> (its, cheapest's)
  std::vector<std::string> order;
  for (const Workload& w : workloads) {
    const size_t frames = checkFrames(w);
    WorkloadResult res;
    res.id = w.id;
    std::map<std::string, LogStats> logs;
    for (const SchemeTimings& s : w.schemes) {
      if (!schemes.count(s.scheme)) order.push_back(s.scheme), schemes[s.scheme].scheme = s.scheme;
      if (s.reps.empty() || frames == 0) {
        res.missing[s.scheme] = s.missing.empty() ? "no timings" : s.missing;
        schemes[s.scheme].missingIn.push_back(w.id);
        continue;
      }
      logs[s.scheme] = logStats(logRepMeans(s));
      if (!s.note.empty()) res.notes[s.scheme] = s.note;
      if (s.reps.size() < 2) res.noInterval.push_back(s.scheme);
      res.costMs[s.scheme] = std::exp(logs[s.scheme].mean);
    }
    for (const auto& [name, cost] : res.costMs)
      if (res.cheapest.empty() || cost < res.costMs[res.cheapest]) res.cheapest = name;
    for (const SchemeTimings& s : w.schemes) {
      if (!logs.count(s.scheme)) continue;
      const LogStats& mine = logs[s.scheme];
      const LogStats& best = logs[res.cheapest];
      if (s.scheme == res.cheapest) {
        res.ratio[s.scheme] = {1, 1, 1};
      } else {
        LogDiff d;
        d.value = mine.mean - best.mean;
        d.add(mine, 1), d.add(best, 1);
        res.ratio[s.scheme] = d.at(confidence);
      }
      const Interval& r = res.ratio[s.scheme];
      if (s.scheme == res.cheapest || std::isnan(r.lo) || r.lo <= 1.0 + margin) {
        res.tied.push_back(s.scheme);
      } else if (s.upperBound) {
        res.tied.push_back(s.scheme);
        res.bounded.push_back(s.scheme);
      }
      pieces[s.scheme].push_back({mine, best});
      ++schemes[s.scheme].workloads;
    }
    for (const std::string& name : res.tied) ++(res.verdict() ? schemes[name].wins : schemes[name].ties);
    v.workloads.push_back(res);
  }
  for (const std::string& name : order) {
    SchemeResult s = schemes[name];
    const auto& p = pieces[name];
    if (p.empty()) {
      s.geomean = {std::nan(""), std::nan(""), std::nan("")};
    } else {
      // mean over workloads of (log cost - log cheapest); the cheapest's own terms are exactly 0.
      LogDiff d;
      const double wgt = 1.0 / double(p.size());
      for (size_t i = 0; i < p.size(); ++i) {
        const auto& [mine, best] = p[i];
        d.value += wgt * (mine.mean - best.mean);
        if (mine.mean != best.mean || mine.var != best.var || mine.n != best.n) d.add(mine, wgt), d.add(best, wgt);
      }
      s.geomean = d.at(confidence);
    }
    v.schemes.push_back(s);
  }
  std::stable_sort(v.schemes.begin(), v.schemes.end(), [](const SchemeResult& a, const SchemeResult& b) {
    if (a.workloads == 0 || b.workloads == 0) return a.workloads > b.workloads;
    return a.geomean.value < b.geomean.value;
  });
  return v;
}

nlohmann::json verdictJson(const SuiteVerdict& v) {
  using nlohmann::json;
  auto interval = [](const Interval& i) {
    if (std::isnan(i.value)) return json(nullptr);
    if (std::isnan(i.lo)) return json{{"value", i.value}, {"lo", nullptr}, {"hi", nullptr}};
    return json{{"value", i.value}, {"lo", i.lo}, {"hi", i.hi}};
  };
  json out = {{"confidence", v.confidence},
              {"margin", v.margin},
              {"method",
               "cost = geometric mean over repetitions of each repetition's mean GPU ms; ratio to the workload's "
               "cheapest with Welch's t interval on the logs of the repetition means; across workloads the "
               "geometric mean of the ratios with a Welch-Satterthwaite t interval; overlapping intervals are a "
               "tie, never a win; with a margin m, an interval whose lower bound is at most 1 + m ties too; a "
               "scheme whose cost is an upper bound (its tuning space ends before the target) ties the cheapest"}};
  json ws = json::array();
  for (const WorkloadResult& w : v.workloads) {
    json r = json::object();
    for (const auto& [k, i] : w.ratio) r[k] = interval(i);
    json jw = {{"id", w.id},
               {"cheapest", w.cheapest.empty() ? json(nullptr) : json(w.cheapest)},
               {"verdict", w.cheapest.empty() ? "no scheme ran"
                           : w.verdict()      ? w.cheapest
                                              : "no verdict"},
               {"tied", w.tied},
               {"tied_at_an_upper_bound", w.bounded},
               {"no_interval", w.noInterval},
               {"cost_ms", w.costMs},
               {"ratio", r},
               {"missing", w.missing},
               {"notes", w.notes}};
    ws.push_back(jw);
  }
  json ss = json::array();
  for (const SchemeResult& s : v.schemes)
    ss.push_back({{"scheme", s.scheme},
                  {"geomean_ratio", interval(s.geomean)},
                  {"workloads", s.workloads},
                  {"wins", s.wins},
                  {"ties", s.ties},
                  {"missing_in", s.missingIn}});
  out["workloads"] = ws;
  out["schemes"] = ss;
  return out;
}

namespace {

std::string paramsLabel(const nlohmann::json& listed) {
  std::string out;
  for (const auto& [k, v] : listed.items()) out += (out.empty() ? "" : ",") + k + "=" + v.dump();
  return out.empty() ? "defaults" : out;
}

std::string workloadId(const CaseData& c) {
  std::string path = std::filesystem::path(c.path).stem().string();
  return (c.terrain.empty() ? "terrain" : c.terrain) + "_" + path + "_" + std::to_string(c.width) + "x" +
         std::to_string(c.height);
}

std::vector<std::vector<double>> repetitions(const nlohmann::json& frames) {
  std::vector<std::vector<double>> reps;
  int last = -1;
  for (const auto& f : frames) {
    if (!f.is_object() || !f.contains("gpu_ms") || !f["gpu_ms"].is_number() || !f.contains("frame")) continue;
    const int frame = f["frame"].get<int>();
    if (reps.empty() || frame <= last) reps.emplace_back();
    reps.back().push_back(f["gpu_ms"].get<double>());
    last = frame;
  }
  return reps;
}

}  // namespace

std::vector<Workload> runWorkloads(const RunData& run) {
  // Case ids sort by scheme first; keep the configs' order of workloads by first appearance.
  std::vector<std::string> order;
  std::map<std::string, std::vector<const CaseData*>> by;
  for (const auto& [id, c] : run.cases) {
    const std::string w = workloadId(c);
    if (!by.count(w)) order.push_back(w);
    by[w].push_back(&c);
  }
  std::vector<Workload> out;
  for (const std::string& w : order) {
    Workload wl{w, {}};
    std::map<std::string, int> perScheme;
    for (const CaseData* c : by[w]) ++perScheme[c->scheme];
    for (const CaseData* c : by[w]) {
      SchemeTimings s;
      s.scheme = perScheme[c->scheme] > 1 ? c->scheme + "(" + paramsLabel(c->listedParams) + ")" : c->scheme;
      if (c->status != "ok") {
        s.missing = c->status + (c->reason.empty() ? "" : ": " + c->reason);
      } else if (c->matched.is_object() && c->matched.value("reachable", true) == false &&
                 !(c->matched["achieved"].is_number() && c->matched["target"].is_number() &&
                   c->matched["achieved"].get<double>() <= c->matched["target"].get<double>())) {
        s.missing = "target unreachable: closest " + c->matched.value("param", std::string("value")) + " " +
                    c->matched["value"].dump() + " reached " + c->matched["achieved"].dump();
      } else {
        if (c->matched.is_object() && c->matched.value("reachable", true) == false)
          s.note = "more accurate than the target at its coarsest: " + c->matched.value("param", std::string("value")) +
                   " " + c->matched["value"].dump() + " reached " + c->matched["achieved"].dump() +
                   " (its cost is an upper bound)";
        s.upperBound = !s.note.empty();
        s.reps = repetitions(c->frames);
        if (s.reps.empty()) s.missing = "no gpu_ms in the case's frames";
      }
      wl.schemes.push_back(s);
    }
    out.push_back(wl);
  }
  return out;
}

SuiteVerdict writeVerdict(const std::string& dir, double confidence, double margin) {
  RunData run = loadRun(dir);
  SuiteVerdict v = suiteVerdict(runWorkloads(run), confidence, margin);
  nlohmann::json j = verdictJson(v);
  j["run_dir"] = dir;
  j["context"] = {{"device", run.context.value("device", "")}, {"driver", run.context.value("driver", "")}};
  writeFileAtomic((std::filesystem::path(dir) / "verdict.json").string(), j.dump(2) + "\n");
  return v;
}

int verdictCommand(const std::vector<std::string>& runDirs, double confidence, double margin) {
  for (const std::string& dir : runDirs) {
    SuiteVerdict v = writeVerdict(dir, confidence, margin);
    std::printf("%s\n", (std::filesystem::path(dir) / "verdict.json").string().c_str());
    std::printf("| scheme | geometric-mean ratio [%g %% interval] | workloads | wins | ties | missing |\n",
                100 * confidence);
    std::printf("|---|---|---:|---:|---:|---:|\n");
    for (const SchemeResult& s : v.schemes) {
      std::string geo = std::isnan(s.geomean.value) ? "-" : std::to_string(s.geomean.value).substr(0, 5);
      if (!std::isnan(s.geomean.lo))
        geo +=
            " [" + std::to_string(s.geomean.lo).substr(0, 5) + ", " + std::to_string(s.geomean.hi).substr(0, 5) + "]";
      std::printf("| %s | %s | %d | %d | %d | %zu |\n", s.scheme.c_str(), geo.c_str(), s.workloads, s.wins, s.ties,
                  s.missingIn.size());
    }
    for (const WorkloadResult& w : v.workloads) {
      std::string what =
          w.cheapest.empty() ? "no scheme ran"
          : w.verdict()      ? w.cheapest + " cheapest, every other interval above 1"
                             : "no verdict: " + std::to_string(w.tied.size()) + " schemes tie" +
                              (margin > 0 ? " (within the margin " + std::to_string(margin).substr(0, 5) + ")" : "") +
                              (w.bounded.empty() ? ""
                                                 : " (" + std::to_string(w.bounded.size()) +
                                                       " at an upper bound of their cost: their tuning space ends "
                                                       "before the target)");
      if (!w.noInterval.empty())
        what += " (" + std::to_string(w.noInterval.size()) + " with fewer than 2 repetitions: no interval)";
      std::printf("%s: %s\n", w.id.c_str(), what.c_str());
    }
  }
  return 0;
}

}  // namespace lb
