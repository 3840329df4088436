// cga-bench: Google Benchmark's runner plus a summary table (each figure with its ratio to the in-project
// GLM baseline of the same run and its performance target). Extra flags: --cga_markdown=FILE writes the summary
// as Markdown; --cga_fail_on_skip makes the exit status 1 when a benchmark was skipped with an error (missing
// model or tool; a job refusing its input), which the smoke test uses. Every other flag is Google
// Benchmark's (--benchmark_filter=REGEX, --benchmark_min_time=S, ...).
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "summary.hpp"

#ifndef CGA_BENCH_MODELS_DIR
#define CGA_BENCH_MODELS_DIR "/usr/share/assimp/models"
#endif
#ifndef CGA_BENCH_CGAGEN
#define CGA_BENCH_CGAGEN ""
#endif
#ifndef CGA_BENCH_SCRIPTS_DIR
#define CGA_BENCH_SCRIPTS_DIR ""
#endif

namespace cga::bench {

namespace {
std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : std::string(fallback);
}
}  // namespace

std::string models_dir() { return env_or("CGA_MODELS_DIR", CGA_BENCH_MODELS_DIR); }
std::string cgagen_path() { return env_or("CGAGEN", CGA_BENCH_CGAGEN); }
std::string scripts_dir() { return env_or("CGA_SCRIPTS_DIR", CGA_BENCH_SCRIPTS_DIR); }

}  // namespace cga::bench

int main(int argc, char** argv) {
  using namespace cga::bench;
  // Take our own flag out before Google Benchmark sees the arguments.
  std::string markdown_path;
  bool fail_on_skip = false;
  // Google Benchmark applies --benchmark_color only to the reporter it makes itself: decide it here.
  bool color = isatty(STDOUT_FILENO) != 0;
  std::vector<char*> args;
  constexpr const char* kMarkdownFlag = "--cga_markdown=";
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], kMarkdownFlag, std::strlen(kMarkdownFlag)) == 0) {
      markdown_path = argv[i] + std::strlen(kMarkdownFlag);
    } else if (std::strcmp(argv[i], "--cga_fail_on_skip") == 0) {
      fail_on_skip = true;
    } else {
      for (const char* off : {"--benchmark_color=false", "--benchmark_color=no", "--benchmark_color=0"})
        if (std::strcmp(argv[i], off) == 0) color = false;
      if (std::strcmp(argv[i], "--help") == 0)
        std::cout << "cga-bench: CGA skinning, motor, pose and generator benchmarks.\n"
                     "  --cga_markdown=FILE   also write the summary table as Markdown to FILE\n"
                     "  --cga_fail_on_skip    exit with status 1 when a benchmark was skipped with an error\n"
                     "Google Benchmark's flags follow.\n\n";
      args.push_back(argv[i]);
    }
  }
  int n = static_cast<int>(args.size());
  args.push_back(nullptr);

  register_skinning_benchmarks();
  register_motor_apply_benchmarks();
  register_pose_benchmarks();
  register_ik_benchmarks();
  register_motion_benchmarks();
  register_generator_benchmarks();

  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 2;

  CapturingReporter reporter(color ? benchmark::ConsoleReporter::OO_Defaults
                                   : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  std::cout << "\nSummary (single core; ratios are speed relative to the baseline measured in this run, >1 = faster)\n"
            << summary_text(reporter.results()) << std::flush;
  if (!markdown_path.empty()) {
    std::ofstream md(markdown_path);
    md << summary_markdown(reporter.results());
    if (!md) {
      std::cerr << "cga-bench: cannot write " << markdown_path << "\n";
      return 1;
    }
  }
  if (fail_on_skip && !reporter.errors().empty()) {
    for (const std::string& e : reporter.errors()) std::cerr << "cga-bench: skipped " << e << "\n";
    return 1;
  }
  return 0;
}
