// cga-demo's command-line parsing (see options.hpp). Every option is spelled out in usage_text().
#include "options.hpp"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

namespace demo {

std::string usage_text(const std::string& default_model) {
  std::string methods;
  for (const cga::SkinningMethodInfo& m : cga::kSkinningMethods) methods += (methods.empty() ? "" : ", ") + std::string(m.name);
  return fmt::format(R"(usage: cga-demo [options]

Loads a skinned, animated character, cross-fades two clips (or the two halves of its only clip) with every
interpolation mode, skins it with every method on the CPU, and prints per mode the time of one pose (sample
two clips + cross-fade + hierarchy + skinning palette), per method the skinning speed, and the deviation
between the methods relative to the character's size. Writes pictures of the posed character per method
and of the twisted two-bone strip as PNG files.

options:
  --model FILE     any Assimp-readable skinned, animated character (default: {0})
  --clip NAME      the clip to fade from; give it twice to name both clips (default: the first two clips;
                   a file with one clip fades from its first half to its second half)
  --method M       skinning method, repeatable or comma-separated: {1}
                   (default: all)
  --mode M         interpolation mode, repeatable or comma-separated: paper, nlerp, screw, glm-matrix,
                   glm-dualquat (default: all five)
  --frames N       poses along the cross-fade, 2..100000 (default 60)
  --out DIR        folder for the PNG pictures, created if missing (default: out)
  --no-pictures    write no pictures
  --web DIR        also write DIR/index.html: every method skinned on the GPU in the browser (WebGPU or
                   WebGL 2, shaders from cgagen's kernels), time and cross-fade sliders, modes paper/nlerp/
                   screw, the twist strip, a heat map; one self-contained file, opens from file://
  --help           this text

exit status: 0 success, 1 the model cannot be used (the message names the file), 2 bad usage.
)",
                     default_model, methods);
}

namespace {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    parts.push_back(text.substr(begin, comma - begin));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return parts;
}

template <class T>
void add_unique(std::vector<T>& list, T value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

}  // namespace

Options parse_options(int argc, const char* const* argv, const std::string& default_model) {
  Options o;
  o.model = default_model;
  std::vector<cga::SkinningMethod> methods;
  std::vector<cga::baseline::PoseMode> modes;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    // "--opt=value" and "--opt value" both work.
    std::string name = arg, inline_value;
    bool has_inline = false;
    if (arg.rfind("--", 0) == 0) {
      const std::size_t eq = arg.find('=');
      if (eq != std::string::npos) name = arg.substr(0, eq), inline_value = arg.substr(eq + 1), has_inline = true;
    }
    auto value = [&]() -> std::string {
      if (has_inline) return inline_value;
      if (i + 1 >= argc) throw UsageError(name + " needs a value");
      // "--model --no-pictures": the next word is an option, not the value (a value that starts with "--"
      // can still be given as --opt=--value).
      const std::string next = argv[i + 1];
      if (next.rfind("--", 0) == 0 && next.size() > 2)
        throw UsageError(name + " needs a value, got the option '" + next + "' (write " + name + "=VALUE)");
      return argv[++i];
    };
    auto no_value = [&]() {
      if (has_inline) throw UsageError(name + " takes no value");
    };
    if (name == "--help" || name == "-h") {
      no_value();
      o.help = true;
    } else if (name == "--model") {
      o.model = value();
      if (o.model.empty()) throw UsageError("--model needs a file name");
    } else if (name == "--clip") {
      if (o.clips.size() == 2) throw UsageError("--clip given more than twice");
      o.clips.push_back(value());
    } else if (name == "--method") {
      for (const std::string& m : split_commas(value())) {
        try {
          add_unique(methods, cga::parse_skinning_method(m));
        } catch (const std::invalid_argument& e) {
          throw UsageError(std::string("--method: ") + e.what());
        }
      }
    } else if (name == "--mode") {
      for (const std::string& m : split_commas(value())) {
        try {
          add_unique(modes, cga::baseline::parse_pose_mode(m));
        } catch (const std::invalid_argument& e) {
          throw UsageError(std::string("--mode: ") + e.what());
        }
      }
    } else if (name == "--frames") {
      const std::string v = value();
      int n = 0;
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
      if (ec != std::errc() || end != v.data() + v.size() || n < 2 || n > 100000)
        throw UsageError("--frames needs an integer in 2..100000, got '" + v + "'");
      o.frames = n;
    } else if (name == "--web") {
      o.web_dir = value();
      if (o.web_dir.empty()) throw UsageError("--web needs a folder");
    } else if (name == "--out") {
      o.out_dir = value();
      if (o.out_dir.empty()) throw UsageError("--out needs a folder name");
    } else if (name == "--no-pictures") {
      no_value();
      o.pictures = false;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "'");
    } else {
      throw UsageError("unexpected argument '" + arg + "' (the model is given with --model FILE)");
    }
  }
  if (!methods.empty()) o.methods = methods;
  if (!modes.empty()) o.modes = modes;
  return o;
}

}  // namespace demo
