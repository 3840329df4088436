// Byte-identical output across processes for every bundled script (runtime/scripts, tests/gen/scripts).
//
// GiNaC's hash values, and with them its term order, move with the address-space layout (ASLR), so a
// generator that leaks GiNaC's order into its choices prints a different (equivalent) kernel from run to
// run. Each script is generated in many processes, the targets taking turns, and every target's texts must
// be equal. A leak typically shows in a third of the runs or more, so 20 runs catch it with near certainty.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace {

std::string run(const std::string& args) {
  std::string cmd = std::string(CGAGEN_EXE) + " " + args + " 2>&1";
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

void check_scripts(const std::filesystem::path& dir) {
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
