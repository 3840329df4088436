// The optimizer's entry point: Kernel -> Program at -O0, -O1 or -O2 (see program.hpp and docs/generator.md).
// The levels live in their own files: level_o0.cpp (as written), substitute.cpp (values substituted into each
// other and the output slot plan), level_o1.cpp (the expanded form, or the statement form past the size
// budget), level_o2.cpp (the cheapest of several forms through the pass pipeline, pipeline.cpp) and
// normalized.cpp (`#pragma normalized` rewriting). Helpers they share are here.
#include <algorithm>
#include <cctype>
#include <map>
#include <stdexcept>

#include "opt/levels.hpp"
#include "symbolic/node_cache.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using namespace detail;

Level parse_level(const std::string& text) {
  if (text == "-O0" || text == "O0" || text == "0") return Level::O0;
  if (text == "-O1" || text == "O1" || text == "1") return Level::O1;
  if (text == "-O2" || text == "O2" || text == "2") return Level::O2;
  throw std::invalid_argument("unknown optimization level '" + text + "' (expected -O0, -O1 or -O2)");
}

namespace detail {

std::string sanitize(const std::string& s) {
  std::string r;
  for (char c : s) r += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  return r;
}

ValueNames::ValueNames(const Kernel& k) {
  Namer namer(k.inputs);
  std::map<std::string, int> seen;
  for (const auto& v : k.values) {
    const int n = ++seen[v.name];
    const std::string prefix = n == 1 ? "v_" : "v" + std::to_string(n) + "_";
    auto& names = names_.emplace_back();
    for (size_t i = 0; i < v.blades.size(); ++i)
      names.push_back(namer.fresh(prefix + sanitize(v.name) + "_" + algebra::blade_ident(v.blades[i])));
  }
}

int blade_pos(const KernelValue& v, algebra::BladeIndex b) {
  auto it = std::find(v.blades.begin(), v.blades.end(), b);
  return it == v.blades.end() ? -1 : static_cast<int>(it - v.blades.begin());
}

Program skeleton(const Kernel& k, Level level) {
  Program p;
  p.name = k.name;
  p.algebra = k.algebra;
  p.level = level;
  p.inputs = k.inputs;
  return p;
}

void drop_unread_temps(Program& p) {
  symbolic::ExHashMap<size_t> index;
  for (size_t i = 0; i < p.temps.size(); ++i) index[p.temps[i].sym] = i;
  std::vector<bool> read(p.temps.size(), false);
  std::vector<size_t> todo;
  auto reads = [&](const ex& e) {
    ExSet syms;
    collect_symbols(e, syms);
    for (const auto& sym : syms)
      if (auto it = index.find(sym); it != index.end() && !read[it->second]) {
        read[it->second] = true;
        todo.push_back(it->second);
      }
  };
  for (const auto& o : p.outputs)
    for (const auto& slot : o.slots) reads(slot.value);
  while (!todo.empty()) {
    const size_t i = todo.back();
    todo.pop_back();
    reads(p.temps[i].value);
  }
  std::vector<Temp> kept;
  for (size_t i = 0; i < p.temps.size(); ++i)
    if (read[i]) kept.push_back(std::move(p.temps[i]));
  p.temps = std::move(kept);
}

}  // namespace detail

namespace {
Program optimize_level(const Kernel& kernel, Level level);
}  // namespace

Program optimize(const Kernel& kernel, Level level) {
  // A fault of GiNaC's inside the optimizer is a bug of cgagen's, but the user still gets a located error
  // (at the first output), never a library's message without a location.
  symbolic::NodeCacheScope caches;
  algebra::Using in(kernel.algebra);
  try {
    return optimize_level(kernel, level);
  } catch (const front::CompileError&) {
    throw;
  } catch (const std::exception& e) {
    const front::SourceLoc at = kernel.outputs.empty() ? front::SourceLoc{1, 1} : kernel.outputs.front().loc;
    throw front::CompileError(at, std::string("cgagen could not optimize this kernel at -O") +
                                      std::to_string(static_cast<int>(level)) + " (" + e.what() +
                                      "); -O0 still works; please report the script");
  }
}

namespace {

Program optimize_level(const Kernel& kernel, Level level) {
  check_normalized(kernel);
  if (level == Level::O0) return optimize_o0(kernel);
  PhaseTimer all("optimize");
  Substituted s = [&] { PhaseTimer t("substitute"); return substitute(kernel); }();
  auto plans = [&] { PhaseTimer t("plan slots"); return plan_slots(kernel, s); }();
  if (level == Level::O1) return optimize_o1(kernel, s, plans);
  return optimize_o2(kernel, s, plans);
}

}  // namespace

}  // namespace cgagen::opt
