// The generator: wall time of one `cgagen -O2 --target cpp` run per bundled script (the built tool as a
// subprocess, so process start and GiNaC set-up count, as in the build), and per kernel the op counts at
// -O0/-O1/-O2 read from `cgagen --stats` ("total: A add, B mul, C div, D call"), reported as counters.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "bench_common.hpp"
#include "cga/testing/joint_chain.hpp"
#include "summary.hpp"

extern char** environ;

namespace cga::bench {

namespace fs = std::filesystem;

namespace {

// Runs argv[0] with argv, stdout to `stdout_path` (or inherited when empty), stderr to /dev/null; returns
// the exit status. Throws when the process cannot start or dies by a signal.
int run_process(const std::vector<std::string>& argv, const std::string& stdout_path) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stdout_path.empty())
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], std::strerror(rc)));
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) throw std::runtime_error("waitpid failed for " + argv[0]);
  if (!WIFEXITED(status)) throw std::runtime_error(argv[0] + " died by a signal");
  return WEXITSTATUS(status);
}

std::string read_file(const fs::path& p) {
  std::string text;
  if (FILE* f = std::fopen(p.c_str(), "rb")) {
    std::array<char, 4096> buf;
    std::size_t got;
    while ((got = std::fread(buf.data(), 1, buf.size(), f)) > 0) text.append(buf.data(), got);
    std::fclose(f);
  }
  return text;
}

// A scratch directory for the generated files, one per process.
fs::path scratch_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / fmt::format("cga-bench-{}", static_cast<long>(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

struct OpCounts {
  long add = 0, mul = 0, div = 0, call = 0;
  long total() const { return add + mul + div + call; }
};

// The "total:" line of `cgagen --stats -O<level>`.
OpCounts stats_at(const fs::path& script, int level, const std::string& algebra) {
  const fs::path out = scratch_dir() / (script.stem().string() + ".stats.txt");
  const int rc = run_process({cgagen_path(), "--algebra", algebra, "--stats", fmt::format("-O{}", level), script.string()},
                             out.string());
  if (rc != 0) throw std::runtime_error(fmt::format("cgagen --stats -O{} {} failed (exit {})", level, script.string(), rc));
  const std::string text = read_file(out);
  static const std::regex total(R"(total:\s*(\d+) add, (\d+) mul, (\d+) div, (\d+) call)");
  std::smatch m;
  if (!std::regex_search(text, m, total))
    throw std::runtime_error("no 'total:' line in cgagen --stats output for " + script.string());
  return {std::stol(m[1]), std::stol(m[2]), std::stol(m[3]), std::stol(m[4])};
}

void bm_generate(benchmark::State& state, const fs::path& script, const std::string& algebra) {
  if (cgagen_path().empty()) {
    state.SkipWithError("this build has no cgagen tool (set CGAGEN=PATH)");
    return;
  }
  std::array<OpCounts, 3> ops;
  try {
    for (int level = 0; level < 3; ++level) ops[level] = stats_at(script, level, algebra);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const fs::path out = scratch_dir() / (script.stem().string() + ".hpp");
  const std::vector<std::string> argv = {cgagen_path(), "--algebra", algebra, "--target", "cpp", "-O2",
                                         "-o",          out.string(), script.string()};
  int failures = 0;
  for (auto _ : state) failures += run_process(argv, "") != 0;
  if (failures) {
    state.SkipWithError(fmt::format("cgagen -O2 failed on {}", script.filename().string()).c_str());
    return;
  }
  for (int level = 0; level < 3; ++level) {
    state.counters[fmt::format("ops_O{}", level)] = static_cast<double>(ops[level].total());
  }
  state.counters["add_O2"] = static_cast<double>(ops[2].add);
  state.counters["mul_O2"] = static_cast<double>(ops[2].mul);
  state.counters["div_O2"] = static_cast<double>(ops[2].div);
  state.counters["call_O2"] = static_cast<double>(ops[2].call);
  state.SetLabel(fmt::format("-O2 ops {:.0f}% of -O0", 100.0 * ops[2].total() / std::max(1L, ops[0].total())));
}

// One generator row: cgagen on `script` in `algebra`, `iterations` runs (each takes tens to hundreds of ms, so a
// few are enough and keep the whole bench short), with its op counts per level.
void register_script(const std::string& name, const fs::path& script, const std::string& algebra, int iterations) {
  benchmark::RegisterBenchmark(name.c_str(), bm_generate, script, algebra)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(iterations);
  add_figure({name, "Generator: cgagen -O2 per bundled script (wall time) and op counts", script.filename().string(),
              Metric::ms_per_iter, "", "", std::nullopt,
              {"ops_O0", "ops_O1", "ops_O2", "add_O2", "mul_O2", "div_O2", "call_O2"}});
}

}  // namespace

void register_generator_benchmarks() {
  std::vector<fs::path> scripts;
  std::error_code ec;
  if (!scripts_dir().empty())
    for (const fs::directory_entry& e : fs::directory_iterator(scripts_dir(), ec))
      if (e.path().extension() == ".clu") scripts.push_back(e.path());
  std::sort(scripts.begin(), scripts.end());  // deterministic order
#if defined(CGA_BENCH_FUZZ_REGRESSIONS_DIR) && defined(CGA_BENCH_CIRCLE3)
  // The generator's worst known inputs: the fuzzer's finds (one took 12 s before the work budget) and
  // circle3's 460000-node expansion. All must stay under a second at every level (docs/generator.md).
  {
    std::vector<fs::path> worst;
    for (const fs::directory_entry& e : fs::directory_iterator(CGA_BENCH_FUZZ_REGRESSIONS_DIR, ec))
      if (e.path().extension() == ".clu") worst.push_back(e.path());
    std::sort(worst.begin(), worst.end());
    worst.push_back(CGA_BENCH_CIRCLE3);
#ifdef CGA_BENCH_GPS
    worst.push_back(CGA_BENCH_GPS);  // Gaalop's GPS example: deep substitution chains (symbolic/dag.hpp)
#endif
    scripts.insert(scripts.end(), worst.begin(), worst.end());
  }
#endif
  for (const fs::path& script : scripts)
    register_script("generator/" + script.stem().string() +
                        (script.parent_path() == fs::path(scripts_dir()) ? "" : " (worst case)"),
                    script, "cga", 5);
  // Chains written as ga-benchmark writes its arm: every carrier an explicit product of all earlier rotors
  // (cga/testing/joint_chain.hpp). The products stage keeps time and ops about linear in n
  // (docs/generator.md, "Products").
  for (int n : {5, 10, 20, 40, 80}) {
    const fs::path script = scratch_dir() / fmt::format("explicit_chain_{}.clu", n);
    if (FILE* f = std::fopen(script.c_str(), "w")) {
      const std::string text = cga::testing::explicit_chain_script(n);
      std::fwrite(text.data(), 1, text.size(), f);
      std::fclose(f);
    }
    register_script(fmt::format("generator/explicit_chain n={}", n), script, "cga", 3);
  }
#ifdef CGA_BENCH_CCGA_200
  // The largest algebra: a 200-line script in ccga (16 vectors), docs/generator.md "Algebras".
  register_script("generator/ccga_200 (--algebra ccga)", CGA_BENCH_CCGA_200, "ccga", 3);
#endif
#ifdef CGA_BENCH_DCGA_200
  // The slowest built-in algebra's 200-line script (tests/gen/test_algebras.cpp's script_200 for dcga).
  register_script("generator/dcga_200 (--algebra dcga)", CGA_BENCH_DCGA_200, "dcga", 3);
#endif
}

}  // namespace cga::bench
