// cga-jacobian-write-chain: writes the n-joint carried chain script of cga/testing/joint_chain.hpp
// (joint_chain_script(n): angles ang1..angN, end point E) for the Jacobian benchmark (bench/jacobian), twice:
// OUT_DIR/chainN.clu as it is (the value kernel) and OUT_DIR/chainN_jac.clu with
// `#pragma jacobian E wrt ang1 ... angN` in front (the derivative kernel). A file is rewritten only when its
// text changes, so that the kernels are not regenerated on every build.
//   usage: cga-jacobian-write-chain N OUT_DIR
#include <cga/testing/joint_chain.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace {

bool write_if_changed(const std::string& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (in) {
    std::stringstream old;
    old << in.rdbuf();
    if (old.str() == text) return true;
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return static_cast<bool>(out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s N OUT_DIR\n", argv[0]);
    return 2;
  }
  const int n = std::atoi(argv[1]);
  if (n < 1 || n > 200) {
    std::fprintf(stderr, "%s: N must be 1..200, got '%s'\n", argv[0], argv[1]);
    return 2;
  }
  const std::string dir = argv[2], stem = dir + "/chain" + std::to_string(n);
  const std::string script = cga::testing::joint_chain_script(n);
  std::string pragma = "#pragma jacobian E wrt";
  for (int k = 1; k <= n; ++k) pragma += " ang" + std::to_string(k);
  if (!write_if_changed(stem + ".clu", script) || !write_if_changed(stem + "_jac.clu", pragma + "\n" + script)) {
    std::fprintf(stderr, "%s: cannot write %s*.clu\n", argv[0], stem.c_str());
    return 1;
  }
  return 0;
}
