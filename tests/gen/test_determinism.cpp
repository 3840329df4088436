// Byte-identical output across processes for every bundled script (runtime/scripts, tests/gen/scripts).
//
// GiNaC's hash values, and with them its term order, move with the address-space layout (ASLR), so a
// generator that leaks GiNaC's order into its choices prints a different (equivalent) kernel from run to
// run. Each script is generated in many processes, the targets taking turns, and every target's texts must
// be equal. A leak typically shows in a third of the runs or more, so 21 runs (7 per target; 9 runs, 3 per
// target, for the two slow scripts) catch it with near certainty. Without ASLR every process would get the
// same layout and the test could not fail, so it first checks that ASLR is on for the processes it starts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <fstream>
#include <sys/personality.h>
#include <sys/wait.h>
#include <vector>

namespace {

// Runs cgagen with args, prefix (e.g. "env VAR=... ") in front of the command.
std::string run_with_prefix(const std::string& prefix, const std::string& args) {
  std::string cmd = prefix + std::string(CGAGEN_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("popen failed: " + cmd);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = pclose(p);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("'" + cmd + "' failed:\n" + out);
  return out;
}

std::string run(const std::string& args) { return run_with_prefix("", args); }

std::vector<std::filesystem::path> scripts_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".clu") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The scripts whose -O2 takes a good fraction of a second get fewer runs (the suite must stay fast).
int runs_for(const std::filesystem::path& script) {
  const std::string stem = script.stem().string();
  return stem == "circle3" || stem == "paper_a1" ? 9 : 21;
}

// ASLR is on for this process and the ones it starts (they inherit its personality).
void require_aslr() {
  std::ifstream in("/proc/sys/kernel/randomize_va_space");
  int mode = -1;
  in >> mode;
  INFO("/proc/sys/kernel/randomize_va_space = " << mode << " (0: ASLR off; the test needs it on)");
  REQUIRE(mode > 0);
  const int persona = personality(0xffffffff);
  INFO("personality " << persona << " (ADDR_NO_RANDOMIZE set, e.g. by setarch -R, turns ASLR off)");
  REQUIRE(persona != -1);
  REQUIRE((persona & ADDR_NO_RANDOMIZE) == 0);
}

void check_scripts(const std::filesystem::path& dir) {
  require_aslr();
  const auto scripts = scripts_in(dir);
  REQUIRE(scripts.size() >= 5);
  const char* targets[] = {"cpp", "glsl", "cuda"};
  for (const auto& script : scripts) {
    std::map<std::string, std::string> first;  // target -> text of its first run
    const int runs = runs_for(script);
    for (int i = 0; i < runs; ++i) {
      const std::string target = targets[i % 3];
      std::string text = run("--target " + target + " " + script.string());
      auto [it, fresh] = first.emplace(target, text);
      INFO(script.filename().string() << " --target " << target << ", run " << i + 1);
      REQUIRE(!text.empty());
      if (!fresh) REQUIRE(text == it->second);
    }
  }
}

}  // namespace

TEST_CASE("runtime scripts: byte-identical output in every process", "[cli][determinism]") {
  check_scripts(std::filesystem::path(CGA_SOURCE_DIR) / "runtime" / "scripts");
}

TEST_CASE("test scripts: byte-identical output in every process", "[cli][determinism]") {
  check_scripts(std::filesystem::path(CGA_TEST_SCRIPTS));
}

TEST_CASE("staged kernels: byte-identical output in every process", "[cli][determinism][stage]") {
  require_aslr();
  const std::string tp = (std::filesystem::path(CGA_SOURCE_DIR) / "runtime" / "scripts" / "transform_point.clu").string();
  const std::string a1 = (std::filesystem::path(CGA_TEST_SCRIPTS) / "paper_a1.clu").string();
  // move_points.clu (examples/point_cloud): a prepared value under sin and cos of a uniform input. The
  // staging pass numbered prepared values in GiNaC's operand order, which differed between processes there.
  const std::string mp =
      (std::filesystem::path(CGA_SOURCE_DIR) / "examples" / "point_cloud" / "move_points.clu").string();
  const std::vector<std::string> cases = {
      "--uniform M " + tp, "--uniform M --stats " + tp, mp,
      "--uniform transX,transY,transZ,axis1X,axis1Y,axis1Z,angle1,d1,trans2X,trans2Y,trans2Z,axis2X,axis2Y,axis2Z,"
      "angle2,d2,alpha " + a1};
  const char* targets[] = {"cpp", "glsl", "cuda"};
  for (const auto& args : cases) {
    std::map<std::string, std::string> first;
    for (int i = 0; i < 12; ++i) {
      const std::string target = targets[i % 3];
      std::string text = run("--target " + target + " " + args);
      auto [it, fresh] = first.emplace(target, text);
      INFO(args << " --target " << target << ", run " << i + 1);
      REQUIRE(!text.empty());
      if (!fresh) REQUIRE(text == it->second);
    }
  }
}

// The fuzzer's finds (fuzz/regressions) at -O2, each in 24 processes with a varied environment (its size
// moves the stack, ASLR the rest). paper_a1_mutant_timeout.clu printed 181 or 182 temporaries depending on
// the process: the sum-factoring pass counted a symbol shared by the terms of a sum only in product terms,
// so t - t*d (GiNaC's order in about half of the processes) was left alone and t*d - t factored. Both the
// code and --stats must be the same in every process.
TEST_CASE("fuzzer finds at -O2: byte-identical code and stats in every process", "[cli][determinism]") {
  require_aslr();
  const auto scripts = scripts_in(std::filesystem::path(CGA_SOURCE_DIR) / "fuzz" / "regressions");
  REQUIRE(scripts.size() >= 4);
  for (const auto& script : scripts) {
    std::string first_code, first_stats;
    for (int i = 0; i < 24; ++i) {
      const std::string env = "env CGA_DETERMINISM_PAD=" + std::string(static_cast<size_t>(1 + 97 * i), 'x') + " ";
      const bool stats = i % 2 == 1;
      std::string text = run_with_prefix(env, std::string(stats ? "--stats " : "") + "-O2 " + script.string());
      INFO(script.filename().string() << (stats ? " --stats" : "") << ", process " << i + 1);
      REQUIRE(!text.empty());
      std::string& first = stats ? first_stats : first_code;
      if (first.empty()) first = text;
      else REQUIRE(text == first);
    }
  }
}
