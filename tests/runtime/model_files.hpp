// Files for the loader tests: bundled test models by path (CGA_MODELS_DIR, assimp-testmodels), a file's
// bytes, and scratch files in a folder of this process (ctest runs test cases as parallel processes: a
// shared folder was removed by one while another wrote into it).
#pragma once

#include <unistd.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace cga_test {

inline std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// This process's scratch folder, removed at exit.
struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("cga_test_models." + std::to_string(::getpid()));
  TempDir() {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// `bytes` written to a file called `name` in this process's scratch folder; its path.
inline std::string temp_file(const std::string& name, const std::string& bytes) {
  static const TempDir dir;
  const std::filesystem::path p = dir.path / name;
  std::ofstream out(p, std::ios::binary);
  out << bytes;
  REQUIRE(out.good());
  return p.string();
}

}  // namespace cga_test
