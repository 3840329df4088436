// The pragmas of a script (pragmas.hpp): each checked where it stands and recorded for the expander.
#include "expand/pragmas.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "algebra/algebra.hpp"
#include "expand/algebra_pragma.hpp"

namespace cgagen::expand_pragmas {

using front::CompileError;
using front::SourceLoc;
using front::Stmt;

namespace {

SourceLoc word_loc(const Stmt& s, size_t i) { return i < s.word_locs.size() ? s.word_locs[i] : s.loc; }


std::vector<algebra::BladeIndex> pragma_blades(const Stmt& s, const std::string& what) {
  if (s.words.size() < 3)
    throw CompileError(s.loc, "'#pragma " + what + "' needs a name and at least one blade");
  std::vector<algebra::BladeIndex> blades;
  for (size_t i = 2; i < s.words.size(); ++i) {
    // Gaalop writes the scalar blade `1` as `1.0` in its pragmas.
    auto b = algebra::parse_blade(s.words[i] == "1.0" ? std::string("1") : s.words[i]);
    if (!b) throw CompileError(word_loc(s, i), "unknown blade '" + s.words[i] + "' in '#pragma " + what + "'");
    if (b->sign < 0)
      throw CompileError(word_loc(s, i), "blade '" + s.words[i] + "' in '#pragma " + what +
                                             "' is not in canonical order; write '" +
                                             algebra::blade_name(b->index) + "'");
    if (std::find(blades.begin(), blades.end(), b->index) != blades.end())
      throw CompileError(word_loc(s, i), "blade '" + s.words[i] + "' is listed twice in '#pragma " + what + "'");
    blades.push_back(b->index);
  }
  return blades;
}


// The names of '#pragma output NAME ...' or '#pragma output {A, B, ...} ...' (the braces may be spread
// over several words); `last` is set to the index of the group's last word.
std::vector<std::string> output_group(const Stmt& s, size_t& last) {
  last = 1;
  if (s.words.size() < 2 || s.words[1].empty() || s.words[1][0] != '{') return {s.words.size() > 1 ? s.words[1] : ""};
  std::string text;
  for (last = 1; last < s.words.size(); ++last) {
    text += s.words[last] + " ";
    if (s.words[last].find('}') != std::string::npos) break;
  }
  if (last == s.words.size()) throw CompileError(word_loc(s, 1), "expected '}' to close the output group");
  if (s.words[last].back() != '}') throw CompileError(word_loc(s, last), "expected a space after '}' in the output group");
  std::vector<std::string> names;
  std::string cur;
  for (char c : text.substr(1, text.find('}') - 1) + ",") {
    if (c == ',') {
      if (cur.empty()) throw CompileError(word_loc(s, 1), "empty name in the output group");
      names.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
        throw CompileError(word_loc(s, 1), std::string("unexpected '") + c + "' in the output group");
      cur += c;
    }
  }
  return names;
}


void range_pragma(const Stmt& s, Kernel& kernel) {
  std::string text;
  for (size_t i = 1; i < s.words.size(); ++i) text += s.words[i];
  auto bad = [&]() { return CompileError(s.loc, "'#pragma range' expects MIN <= NAME <= MAX"); };
  size_t a = text.find("<="), b = a == std::string::npos ? a : text.find("<=", a + 2);
  if (b == std::string::npos || text.find("<=", b + 2) != std::string::npos) throw bad();
  std::string lo = text.substr(0, a), name = text.substr(a + 2, b - a - 2), hi = text.substr(b + 2);
  auto num = [&](const std::string& t) {
    char* end = nullptr;
    double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size()) throw bad();
    return v;
  };
  ScalarRange r;
  r.name = name;
  r.min = num(lo);
  r.max = num(hi);
  if (name.empty()) throw bad();
  if (r.min > r.max) throw CompileError(s.loc, "'#pragma range' for '" + name + "' has MIN > MAX");
  kernel.ranges.push_back(r);
}

}  // namespace


void Pragmas::apply(const Stmt& s, Kernel& kernel, PragmaHost& host) {
  if (s.words.empty()) throw CompileError(s.loc, "empty '#pragma'");
  const std::string& kind = s.words[0];
  if (kind == "output") {
    // Gaalop also names a group of outputs that share the blades: #pragma output {a, b} e1 e2.
    if (s.words.size() < 2) throw CompileError(s.loc, "'#pragma output' needs a name and at least one blade");
    size_t last = 1;
    std::vector<std::string> names = output_group(s, last);
    Stmt rest = s;  // the blades after the group, where pragma_blades expects them (words[2...])
    rest.words.assign(s.words.begin(), s.words.begin() + 2);
    rest.words.insert(rest.words.end(), s.words.begin() + static_cast<long>(last) + 1, s.words.end());
    rest.word_locs.assign(s.word_locs.begin(), s.word_locs.begin() + std::min<size_t>(2, s.word_locs.size()));
    for (size_t i = last + 1; i < s.word_locs.size(); ++i) rest.word_locs.push_back(s.word_locs[i]);
    auto blades = pragma_blades(rest, "output");
    for (const auto& n : names) outputs_[n] = {word_loc(s, 1), blades};
  } else if (kind == "onlyEvaluate") {
    // Gaalop keeps these values as temporaries of its own (a boundary for its inlining); they are never
    // outputs. Here their values stay in the kernel like those of '!x = e;' (emitted at -O0); the outputs
    // are the same either way. A name that is never assigned is an error.
    if (s.words.size() < 2) throw CompileError(s.loc, "'#pragma onlyEvaluate' needs at least one name");
    for (size_t i = 1; i < s.words.size(); ++i)
      if (!host.is_assigned(s.words[i]))
        throw CompileError(word_loc(s, i), "'#pragma onlyEvaluate' names '" + s.words[i] +
                                               "', which the script never assigns");
      else
        only_evaluate_.insert(s.words[i]);
  } else if (kind == "in2out") {
    in2out_pragma(s);
  } else if (kind == "normalize") {
    // From here on every `?x = e;` outputs x = e / abs(e) (Gaalop rewrites the source the same way).
    if (s.words.size() != 1) throw CompileError(word_loc(s, 1), "'#pragma normalize' takes no words");
    normalize_outputs_ = true;
  } else if (kind == "return") {
    throw CompileError(word_loc(s, 0), "'#pragma return' is not supported: it wraps outputs in a type written "
                                       "as target-language text (Gaalop: C# and Python only), which cgagen cannot "
                                       "check for its other targets; use the outputs as arrays, or --return/--pack");
  } else if (kind == "insert") {
    throw CompileError(word_loc(s, 0), "'#pragma insert' is not supported: it pastes text verbatim into the "
                                       "generated code, and one script here feeds several target languages");
  } else if (kind == "segments" || kind == "triangles") {
    // Drawing hints for Gaalop's visualizer (Ganja); they compute nothing, and code generation ignores them.
  } else if (kind == "count") {
    throw CompileError(word_loc(s, 0), "'#pragma count' (a loop counter of Gaalop 2.0) is not supported: loops "
                                       "run a constant number of times ('#pragma unroll N' before 'loop')");
  } else if (kind == "input") {
    auto blades = pragma_blades(s, "input");
    const std::string& name = s.words[1];
    if (host.is_basis_name(name))
      throw CompileError(word_loc(s, 1), "cannot declare basis vector '" + name + "' as an input");
    if (host.is_defined(name))
      throw CompileError(word_loc(s, 1), "'" + name + "' is already used before its '#pragma input'");
    host.declare_input(name, blades);
  } else if (kind == "range") {
    range_pragma(s, kernel);
  } else if (kind == "uniform") {
    // Rates for the staging pass (opt/stage.cpp), which checks the names once all inputs are known.
    if (s.words.size() < 2) throw CompileError(s.loc, "'#pragma uniform' needs at least one input name");
    for (size_t i = 1; i < s.words.size(); ++i) kernel.uniforms.push_back({s.words[i], word_loc(s, i)});
  } else if (kind == "normalized") {
    // A promise about inputs (X ~X = 1) for -O2 (opt/levels.cpp checks the names once all inputs are known).
    if (s.words.size() < 2) throw CompileError(s.loc, "'#pragma normalized' needs at least one input name");
    for (size_t i = 1; i < s.words.size(); ++i) kernel.normalized.push_back({s.words[i], word_loc(s, i)});
  } else if (kind == "algebra") {
    // Chosen before expansion (expand/algebra_pragma.hpp); here only checked, so that no caller expands the
    // script in another algebra without a word.
    if (s.words.size() == 2 && expand_algebra_pragma::algebra_name(s.words[1]) != algebra::current().name())
      throw CompileError(word_loc(s, 1), "'#pragma algebra " + s.words[1] + "': the script is being compiled in '" +
                                             algebra::current().name() + "' (a conflicting --algebra or ALGEBRA?)");
  } else if (kind == "versor") {
    // A promise that a name's value is a versor for every input passed: division by it takes ~x / <x ~x>_0.
    if (s.words.size() < 2) throw CompileError(s.loc, "'#pragma versor' needs at least one name");
    // (Whether each name gets a value is checked once the script is expanded: the pragma may come first.)
    for (size_t i = 1; i < s.words.size(); ++i) {
      if (host.is_basis_name(s.words[i]))
        throw CompileError(word_loc(s, i), "'#pragma versor': '" + s.words[i] + "' is a basis vector");
      versors_.push_back({s.words[i], word_loc(s, i)});
    }
  } else if (kind == "jacobian") {
    // Names are checked once the script is expanded (expand/jacobian.cpp): the outputs come later.
    JacobianPragma j{s.loc, {}, {}};
    size_t i = 1;
    for (; i < s.words.size() && s.words[i] != "wrt"; ++i) j.outputs.push_back({s.words[i], word_loc(s, i)});
    if (i == s.words.size()) throw CompileError(s.loc, "'#pragma jacobian' expects [OUTPUT...] wrt INPUT...");
    for (++i; i < s.words.size(); ++i) j.wrt.push_back({s.words[i], word_loc(s, i)});
    if (j.wrt.empty()) throw CompileError(s.loc, "'#pragma jacobian ... wrt' names no input");
    jacobians_.push_back(std::move(j));
  } else {
    throw CompileError(word_loc(s, 0), "unknown pragma '" + kind + "' (expected output, input, range, uniform, "
                                       "normalized, versor, jacobian, algebra, onlyEvaluate, in2out, normalize, "
                                       "segments or triangles)");
  }
}


// #pragma in2out a, b -> c, d: the generated function's inputs and outputs, in this order. As in Gaalop,
// every input and every output must be listed, and only those; checked once the script is expanded.
void Pragmas::in2out_pragma(const Stmt& s) {
  std::string text;
  for (size_t i = 1; i < s.words.size(); ++i) text += s.words[i] + " ";
  size_t arrow = text.find("->");
  if (arrow == std::string::npos || text.find("->", arrow + 2) != std::string::npos)
    throw CompileError(s.loc, "'#pragma in2out' expects INPUT, ... -> OUTPUT, ... with one '->'");
  auto split = [&](const std::string& part) {
    std::vector<std::string> names;
    std::string cur;
    for (char c : part + ",") {
      if (c == ',') {
        if (!cur.empty()) names.push_back(cur);
        cur.clear();
      } else if (c != ' ') {
        cur += c;
      }
    }
    return names;
  };
  if (in2out_) throw CompileError(s.loc, "a second '#pragma in2out'");
  in2out_ = In2Out{s.loc, split(text.substr(0, arrow)), split(text.substr(arrow + 2))};
}


void Pragmas::apply_in2out(Kernel& kernel) const {
  if (!in2out_) return;
  const In2Out& io = *in2out_;
  std::vector<KernelInput> inputs;
  for (const auto& n : io.inputs) {
    auto it = std::find_if(kernel.inputs.begin(), kernel.inputs.end(), [&](const KernelInput& k) { return k.name == n; });
    if (it == kernel.inputs.end())
      throw CompileError(io.loc, "'#pragma in2out' lists '" + n + "', which is not an input of the script");
    if (std::any_of(inputs.begin(), inputs.end(), [&](const KernelInput& k) { return k.name == n; }))
      throw CompileError(io.loc, "'#pragma in2out' lists input '" + n + "' twice");
    inputs.push_back(*it);
  }
  for (const auto& k : kernel.inputs)
    if (std::find(io.inputs.begin(), io.inputs.end(), k.name) == io.inputs.end())
      throw CompileError(io.loc, "'#pragma in2out' does not list input '" + k.name + "'");
  std::vector<KernelOutput> outputs;
  for (const auto& n : io.outputs) {
    auto it = std::find_if(kernel.outputs.begin(), kernel.outputs.end(), [&](const KernelOutput& k) { return k.name == n; });
    if (it == kernel.outputs.end())
      throw CompileError(io.loc, "'#pragma in2out' lists '" + n + "', which is not an output of the script");
    if (std::any_of(outputs.begin(), outputs.end(), [&](const KernelOutput& k) { return k.name == n; }))
      throw CompileError(io.loc, "'#pragma in2out' lists output '" + n + "' twice");
    outputs.push_back(*it);
  }
  for (const auto& k : kernel.outputs)
    if (std::find(io.outputs.begin(), io.outputs.end(), k.name) == io.outputs.end())
      throw CompileError(io.loc, "'#pragma in2out' does not list output '" + k.name + "'");
  kernel.inputs = std::move(inputs);
  kernel.outputs = std::move(outputs);
}

bool Pragmas::only_evaluate(const std::string& name) const { return only_evaluate_.count(name) > 0; }

const OutputPragma* Pragmas::output(const std::string& name) const {
  auto it = outputs_.find(name);
  return it == outputs_.end() ? nullptr : &it->second;
}

void Pragmas::check_outputs(const std::function<bool(const std::string&)>& is_output) const {
  for (const auto& [name, p] : outputs_)
    if (!is_output(name)) throw CompileError(p.loc, "'#pragma output' names '" + name + "', which is not an output");
}

}  // namespace cgagen::expand_pragmas
