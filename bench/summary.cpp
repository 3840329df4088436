// The figure registry, the capturing reporter and the summary tables (see summary.hpp).
#include "summary.hpp"

#include <cmath>

#include <fmt/format.h>

namespace cga::bench {

namespace {

std::vector<Figure>& figures() {
  static std::vector<Figure> all;
  return all;
}

using Run = benchmark::BenchmarkReporter::Run;
using Results = std::map<std::string, Run>;

bool higher_is_better(Metric m) { return m == Metric::mega_items_per_s; }

// Real time when the benchmark asked for it (UseRealTime: a subprocess), otherwise the process's CPU time,
// which a machine shared with builds disturbs less.
double seconds_per_iteration(const Run& r) {
  // The adjusted times are in r.time_unit; convert to seconds whatever unit the benchmark chose.
  double per_s = 1.0;
  switch (r.time_unit) {
    case benchmark::kNanosecond: per_s = 1e9; break;
    case benchmark::kMicrosecond: per_s = 1e6; break;
    case benchmark::kMillisecond: per_s = 1e3; break;
    case benchmark::kSecond: per_s = 1.0; break;
  }
  const bool real = !r.run_name.time_type.empty();
  return (real ? r.GetAdjustedRealTime() : r.GetAdjustedCPUTime()) / per_s;
}

// The figure's value, or nothing when the run lacks what the metric needs.
std::optional<double> value_of(const Figure& f, const Run& r) {
  switch (f.metric) {
    case Metric::mega_items_per_s:
    case Metric::ns_per_item: {
      auto it = r.counters.find("items_per_second");
      if (it == r.counters.end() || !(it->second.value > 0)) return std::nullopt;
      const double ips = it->second.value;
      return f.metric == Metric::mega_items_per_s ? ips / 1e6 : 1e9 / ips;
    }
    case Metric::us_per_iter: return seconds_per_iteration(r) * 1e6;
    case Metric::ms_per_iter: return seconds_per_iteration(r) * 1e3;
  }
  return std::nullopt;
}

std::string format_value(Metric m, double v) {
  switch (m) {
    case Metric::mega_items_per_s: return fmt::format("{:.1f} M/s", v);
    case Metric::ns_per_item: return fmt::format("{:.2f} ns", v);
    case Metric::us_per_iter: return fmt::format("{:.2f} µs", v);
    case Metric::ms_per_iter: return fmt::format("{:.1f} ms", v);
  }
  return fmt::format("{}", v);
}

std::string format_counter(double v) {
  if (v == std::floor(v) && std::fabs(v) < 1e12) return fmt::format("{:.0f}", v);
  return fmt::format("{:.3g}", v);
}

struct Row {
  const Figure* figure;
  std::optional<double> value;
  std::optional<double> speedup;  // > 1: faster than the baseline
  std::string why_missing;        // when value is empty
  std::string target_status;      // "met" / "missed" / ""
  std::string notes;
};

Row make_row(const Figure& f, const Results& results) {
  Row row{&f, std::nullopt, std::nullopt, "", "", ""};
  auto it = results.find(f.benchmark);
  if (it == results.end()) {
    row.why_missing = "not run";
    return row;
  }
  const Run& r = it->second;
  if (r.error_occurred) {
    row.why_missing = "skipped: " + r.error_message;
    return row;
  }
  row.value = value_of(f, r);
  if (!row.value) {
    row.why_missing = "no result";
    return row;
  }
  if (!f.baseline.empty() && f.baseline != f.benchmark) {
    auto b = results.find(f.baseline);
    if (b != results.end() && !b->second.error_occurred) {
      // The baseline is read with this figure's metric.
      if (auto bv = value_of(f, b->second); bv && *bv > 0)
        row.speedup = higher_is_better(f.metric) ? *row.value / *bv : *bv / *row.value;
    }
  }
  if (f.target) {
    const bool met = higher_is_better(f.metric) ? *row.value >= f.target->value : *row.value <= f.target->value;
    row.target_status = met ? "met" : "missed";
  }
  for (const std::string& c : f.counters) {
    auto ci = r.counters.find(c);
    if (ci == r.counters.end()) continue;
    if (!row.notes.empty()) row.notes += ", ";
    row.notes += c + "=" + format_counter(ci->second.value);
  }
  if (!r.report_label.empty()) row.notes += (row.notes.empty() ? "" : "; ") + r.report_label;
  return row;
}

std::string ratio_text(const Row& row) {
  const Figure& f = *row.figure;
  if (f.baseline.empty() || f.baseline == f.benchmark) return f.baseline.empty() ? "" : "baseline";
  if (!row.speedup) return "n/a (baseline " + f.baseline_label + " missing)";
  return fmt::format("{:.2f}x {}", *row.speedup, f.baseline_label);
}

}  // namespace

void add_figure(Figure figure) { figures().push_back(std::move(figure)); }

void CapturingReporter::ReportRuns(const std::vector<Run>& runs) {
  for (const Run& r : runs) {
    // The registered name, without the "/real_time" or "/iterations:N" suffixes Google Benchmark appends.
    const std::string name = r.run_name.function_name;
    if (r.error_occurred && r.run_type == Run::RT_Iteration) errors_.push_back(name + ": " + r.error_message);
    if (r.run_type == Run::RT_Iteration) {
      // With repetitions the median aggregate (below) replaces the single runs.
      if (!results_.count(name) || results_[name].run_type == Run::RT_Iteration) results_[name] = r;
    } else if (r.aggregate_name == "median") {
      results_[name] = r;
    }
  }
  ConsoleReporter::ReportRuns(runs);
}

std::string summary_markdown(const Results& results) {
  std::string out;
  std::string section;
  for (const Figure& f : figures()) {
    if (f.section != section) {
      section = f.section;
      out += fmt::format("\n### {}\n\n", section);
      out += "| Case | Result | vs. baseline (>1 = faster) | Target | Notes |\n";
      out += "|---|---:|---|---|---|\n";
    }
    const Row row = make_row(f, results);
    const std::string value = row.value ? format_value(f.metric, *row.value) : row.why_missing;
    const std::string target = f.target ? f.target->text + (row.target_status.empty() ? "" : " — " + row.target_status) : "";
    out += fmt::format("| {} | {} | {} | {} | {} |\n", f.label, value, ratio_text(row), target, row.notes);
  }
  return out;
}

std::string summary_text(const Results& results) {
  std::string out;
  std::string section;
  for (const Figure& f : figures()) {
    if (f.section != section) {
      section = f.section;
      out += fmt::format("\n{}\n", section);
    }
    const Row row = make_row(f, results);
    if (!row.value) {
      out += fmt::format("  {}: {}\n", f.label, row.why_missing);
      continue;
    }
    std::string line = fmt::format("  {}: {}", f.label, format_value(f.metric, *row.value));
    const std::string ratio = ratio_text(row);
    if (!ratio.empty()) line += " = " + ratio;
    if (f.target) line += fmt::format(" (target {}: {})", f.target->text, row.target_status);
    if (!row.notes.empty()) line += "  [" + row.notes + "]";
    out += line + "\n";
  }
  return out;
}

}  // namespace cga::bench
