// The summary of a cga-bench run: every benchmark registers a Figure (what to read from its result, which
// benchmark is its baseline, which performance target applies), a capturing reporter keeps the results, and at
// the end one table prints each figure with its ratio to the baseline measured in the same run, as text on
// stdout and optionally as Markdown (the table README carries).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace cga::bench {

// How a figure is read from a benchmark run.
enum class Metric {
  mega_items_per_s,  // items_per_second / 1e6 (skinning: M vertices/s); higher is better
  ns_per_item,       // 1e9 / items_per_second (ns/point); lower is better
  us_per_iter,       // real time per iteration in µs (one pose); lower is better
  ms_per_iter,       // real time per iteration in ms (one generator run); lower is better
};

// A performance target: the figure must reach `value` (>= for throughputs, <= for times).
struct Target {
  double value;
  std::string text;  // as the table prints it, e.g. ">= 300 M vert/s"
};

struct Figure {
  std::string benchmark;  // Google Benchmark name (as registered)
  std::string section;    // table section, e.g. "Skinning, positions (1 M vertices, 64 bones, 4 influences)"
  std::string label;      // row name, e.g. "cga-points"
  Metric metric = Metric::mega_items_per_s;
  std::string baseline;   // benchmark name of the baseline (empty: none, or this row is the baseline)
  std::string baseline_label;
  std::optional<Target> target;
  // User counters printed in the Notes column as name=value (e.g. op counts), in this order.
  std::vector<std::string> counters;
};

// Registers a figure for the summary (call before benchmarks run; the order is the table's order).
void add_figure(Figure figure);

// A console reporter that also keeps every run's result by benchmark name (the median when repeated).
class CapturingReporter : public benchmark::ConsoleReporter {
 public:
  explicit CapturingReporter(OutputOptions options) : ConsoleReporter(options) {}
  void ReportRuns(const std::vector<Run>& runs) override;
  const std::map<std::string, Run>& results() const { return results_; }
  // "name: message" of every run skipped with an error, in the order they ran.
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  std::map<std::string, Run> results_;
  std::vector<std::string> errors_;
};

// The summary as Markdown (a table per section). Figures whose benchmark did not run (filtered out or
// skipped with an error) are listed as such, not dropped.
std::string summary_markdown(const std::map<std::string, benchmark::BenchmarkReporter::Run>& results);

// One line per figure, e.g. "cga-points: 312 M vert/s = 1.9x glm lbs (target >= 300 M vert/s: met)".
std::string summary_text(const std::map<std::string, benchmark::BenchmarkReporter::Run>& results);

}  // namespace cga::bench
