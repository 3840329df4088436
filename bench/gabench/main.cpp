// cga-gabench: ga-benchmark's operation set (bench/gabench/gabench.hpp) on the registered implementations.
// Every case's every implementation is first checked against the oracle (models.cpp) on the first samples,
// and a wrong result ends the run with exit status 1; then (unless --gabench_check_only) each case is timed,
// cgagen and GATL back to back, with ga-benchmark's names and statistics (Google Benchmark JSON through
// --benchmark_out), and a table of geomean time ratios cgagen/GATL per operation and model is printed.
//   cga-gabench [--gabench_models=c3ga,e3ga] [--gabench_ops=GeometricProduct,...] [--gabench_check_only]
//               [--gabench_checks=N] [--gabench_repetitions=N] [Google Benchmark flags]
#include "models.hpp"

#include <sys/utsname.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace gabench;

std::set<std::string> split(const std::string& s) {
  std::set<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.insert(item);
  return out;
}

struct Options {
  std::set<std::string> models, ops;
  bool check_only = false;
  int checks = 32;
  int repetitions = 30;  // ga-benchmark's
};

// Our flags out of argv (the rest is Google Benchmark's).
Options parse(int& argc, char** argv) {
  Options o;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* flag) -> const char* {
      const std::size_t n = std::strlen(flag);
      return a.compare(0, n, flag) == 0 ? argv[i] + n : nullptr;
    };
    if (const char* v = value("--gabench_models=")) o.models = split(v);
    else if (const char* v = value("--gabench_ops=")) o.ops = split(v);
    else if (const char* v = value("--gabench_checks=")) o.checks = std::atoi(v);
    else if (const char* v = value("--gabench_repetitions=")) o.repetitions = std::atoi(v);
    else if (a == "--gabench_check_only") o.check_only = true;
    else argv[out++] = argv[i];
  }
  argc = out;
  return o;
}

// ga-benchmark's arguments: which random blades each operation takes.
bool invertible_a(const std::string& op) { return op == "Inversion" || op == "Normalization"; }
bool invertible_b(const std::string& op) { return op == "InverseGeometricProduct"; }

struct Case {
  std::string model, op;
  int ga = 0, gb = -1;
  std::map<std::string, Side> sides;  // solution -> side
};

// GATL's results that differ from the operation's definition, found by the checks below: they are reported at
// every run and timed anyway (the difference is GATL's, not the harness's). GATL's unit() of a pseudoscalar
// a I of the Euclidean models is +I also for a < 0 (as if sqrt(a a) were a).
bool known_deviation(const Case& c, const std::string& solution) {
  if (solution != "GATL" || c.op != "Normalization") return false;
  return (c.model == "e3ga" && c.ga == 3) || (c.model == "h3ga" && c.ga == 4);
}

std::string case_name(const Case& c, const std::string& solution) {
  static const std::string context = [] {
    utsname u{};
    uname(&u);
    char compiler[64];
    std::snprintf(compiler, sizeof compiler, "%d.%d.%d", __GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__);
#if defined(__clang__)
    const char* id = "Clang";
#else
    const char* id = "GNU";
#endif
    return std::string("SystemName:") + u.sysname + "/SystemVersion:" + u.release + "/CompilerID:" + id +
           "/CompilerVersion:" + compiler;
  }();
  const Model& m = model(c.model);
  char mid[8];
  std::snprintf(mid, sizeof mid, "0x%02X", m.id);
  std::string s = std::string("GABM_") + (c.gb < 0 ? "UnaryOperation_" : "BinaryOperation_") + c.op + "/" + context +
                  "/Solution:" + solution + "/Model:" + mid + "/D:" + std::to_string(m.d);
  if (c.gb < 0) return s + "/Grade:" + std::to_string(c.ga);
  return s + "/LeftGrade:" + std::to_string(c.ga) + "/RightGrade:" + std::to_string(c.gb);
}

// Collects the time per call of each benchmark and prints one short line per case and implementation (the full
// names and ga-benchmark's statistics go to --benchmark_out's JSON). Each repetition's time is the mean real
// time per call over the batch of kSamples calls; the figure kept is the median over the repetitions (the
// mean is in the JSON), which a descheduled repetition on a shared machine does not move.
class Collector : public benchmark::BenchmarkReporter {
 public:
  std::map<std::string, double> median;
  std::map<std::string, std::string> label;  // benchmark name -> short label
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      const std::string name = r.run_name.function_name;
      if (r.error_occurred) {
        std::printf("%-48s ERROR %s\n", label[name].c_str(), r.error_message.c_str());
        continue;
      }
      if (r.run_type != Run::RT_Aggregate || r.aggregate_name != "median") continue;
      const double ns = r.GetAdjustedRealTime() * 1e6;  // the unit is ms, ga-benchmark's
      median[name] = ns;
      std::printf("%-48s %9.2f ns\n", label[name].c_str(), ns);
      std::fflush(stdout);
    }
  }
};

}  // namespace

int main(int argc, char** argv) try {
  Options opt = parse(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  // The cases: the registered implementations grouped by (model, op, grades).
  std::map<std::string, Case> cases;
  for (const Entry& e : registry()) {
    if (!opt.models.empty() && !opt.models.count(e.model)) continue;
    if (!opt.ops.empty() && !opt.ops.count(e.op)) continue;
    char key[160];
    std::snprintf(key, sizeof key, "%s/%s/%d/%d", e.model.c_str(), e.op.c_str(), e.ga, e.gb);
    Case& c = cases[key];
    c.model = e.model, c.op = e.op, c.ga = e.ga, c.gb = e.gb;
  }
  if (cases.empty()) {
    std::fprintf(stderr, "cga-gabench: no case selected\n");
    return 2;
  }

  // The inputs, shared by the cases: (model, role, grade) -> blades.
  std::map<std::string, std::unique_ptr<BladeSet>> sets;
  auto blades = [&](const Model& m, const std::string& role, int grade, bool invertible) -> const BladeSet* {
    const std::string key = m.name + "/" + role + (invertible ? "i" : "") + "/" + std::to_string(grade);
    auto& p = sets[key];
    if (!p) p = std::make_unique<BladeSet>(make_blades(m, grade, role + (invertible ? "i" : ""), invertible));
    return p.get();
  };

  // Build each side and check it against the oracle before anything is timed.
  int checked = 0, failed = 0;
  for (auto& [key, c] : cases) {
    const Model& m = model(c.model);
    Inputs in;
    in.a = blades(m, c.gb < 0 ? "unary" : "left", c.ga, invertible_a(c.op));
    if (c.gb >= 0) in.b = blades(m, "right", c.gb, invertible_b(c.op));
    for (const Entry& e : registry())
      if (e.model == c.model && e.op == c.op && e.ga == c.ga && e.gb == c.gb) c.sides[e.solution] = e.make(in);
    std::set<std::string> wrong;  // a side is reported once, at its first wrong sample
    for (int i = 0; i < opt.checks && i < static_cast<int>(kSamples); ++i) {
      const og::MV a = oracle_value(m, *in.a, static_cast<std::size_t>(i));
      og::MV b;
      if (in.b) b = oracle_value(m, *in.b, static_cast<std::size_t>(i));
      const Named want = reference(m, c.op, a, in.b ? &b : nullptr);
      for (auto& [solution, side] : c.sides) {
        if (wrong.count(solution)) continue;
        const Named got = side.eval(static_cast<std::size_t>(i));
        const double d = rel_diff(want, got);
        if (d <= 1e-9) continue;
        wrong.insert(solution);
        const bool known = known_deviation(c, solution);
        if (!known) ++failed;
        std::fprintf(stderr, "cga-gabench: %s %s %s sample %d: relative difference %g\n  oracle:",
                     known ? "known deviation (timed anyway):" : "WRONG", solution.c_str(), key.c_str(), i, d);
        for (const auto& [k, v] : want) std::fprintf(stderr, " %s=%.17g", k.c_str(), v);
        std::fprintf(stderr, "\n  %s:", solution.c_str());
        for (const auto& [k, v] : got) std::fprintf(stderr, " %s=%.17g", k.c_str(), v);
        std::fprintf(stderr, "\n");
      }
    }
    checked += static_cast<int>(c.sides.size());
  }
  std::printf("cga-gabench: %zu cases, %d implementations checked against the oracle on %d samples each: %s\n",
              cases.size(), checked, opt.checks, failed ? "FAILED" : "all equal");
  if (failed) std::printf("cga-gabench: %d implementations WRONG\n", failed);
  if (failed) return 1;
  if (opt.check_only) return 0;

  // Time: each case's implementations back to back (the order alternating from case to case), each with
  // ga-benchmark's statistics over repetitions of kSamples calls.
  Collector collector;
  int n = 0;
  for (auto& [key, c] : cases) {
    std::vector<std::string> order;
    for (auto& [solution, side] : c.sides) order.push_back(solution);
    if (n++ % 2) std::reverse(order.begin(), order.end());
    for (const std::string& solution : order) {
      collector.label[case_name(c, solution)] = key + " " + solution;
      benchmark::RegisterBenchmark(case_name(c, solution).c_str(), c.sides[solution].run)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(static_cast<benchmark::IterationCount>(kSamples))
          ->Repetitions(opt.repetitions)
          ->ReportAggregatesOnly(true)
          ->DisplayAggregatesOnly(true);
    }
  }
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();

  // Geomean ratio cgagen/GATL per operation and model (median time per call, over the grade pairs), for each
  // cgagen row: as called (pointers to the arguments) and on local copies of them ("cgagen-local").
  std::map<std::string, std::map<std::string, std::pair<double, int>>> table;  // op -> column -> (sum log, n)
  std::set<std::string> columns;
  for (auto& [key, c] : cases) {
    const auto gl = collector.median.find(case_name(c, "GATL"));
    if (gl == collector.median.end() || gl->second <= 0) continue;
    for (const char* solution : {"cgagen", "cgagen-local"}) {
      const auto cg = collector.median.find(case_name(c, solution));
      if (cg == collector.median.end()) continue;
      const std::string column = c.model + (std::string(solution) == "cgagen" ? "" : " (local args)");
      auto& cell = table[c.op][column];
      cell.first += std::log(cg->second / gl->second);
      cell.second += 1;
      auto& all = table["all (every case)"][column];
      all.first += std::log(cg->second / gl->second);
      all.second += 1;
      columns.insert(column);
    }
  }
  if (table.empty()) return 0;
  std::printf("\nGeomean time ratio cgagen/GATL over the grade pairs (below 1: cgagen faster)\n\n| operation |");
  for (const auto& column : columns) std::printf(" %s |", column.c_str());
  std::printf("\n|---|");
  for (std::size_t i = 0; i < columns.size(); ++i) std::printf("---:|");
  std::printf("\n");
  auto row = [&](const std::string& op) {
    std::printf("| %s |", op.c_str());
    for (const auto& column : columns) {
      const auto it = table[op].find(column);
      if (it == table[op].end()) std::printf(" |");
      else std::printf(" %.2f |", std::exp(it->second.first / it->second.second));
    }
    std::printf("\n");
  };
  for (const auto& [op, cells] : table)
    if (op != "all (every case)") row(op);
  row("all (every case)");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "cga-gabench: %s\n", e.what());
  return 1;
}
