// consumer_io: cgagen::io, the Assimp importer, from an installed cgagen: a missing file is refused with a
// cga::LoadError that names it (which needs the installed static library and its Assimp dependency to link).
// Exit status 0 when it is, 1 otherwise.
#include <cstdio>
#include <string>

#include <cga/io/loader.hpp>  // cgagen::io

int main() {
  const std::string path = "no-such-character.fbx";
  try {
    cga::load_character(path);
  } catch (const cga::LoadError& e) {
    if (std::string(e.what()).find(path) != std::string::npos) {
      std::printf("consumer_io: ok (%s)\n", e.what());
      return 0;
    }
    std::fprintf(stderr, "consumer_io: the message does not name the file: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "consumer_io: loading a missing file did not throw cga::LoadError\n");
  return 1;
}
