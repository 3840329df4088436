// The staging pass: an optimized Program -> NAME_prepare(uniforms) and NAME(prepared, elements).
//
// How the split is found. The program's temporaries that read a per-element input (directly or through other
// temporaries) are substituted into the outputs, so each output is one expression over the per-element
// inputs, the uniform inputs and the uniform-only temporaries. Two candidate forms of each output are built:
//  - collected: the expression expanded and its terms grouped by their per-element part (the per-element
//    factors of a term: x, x*y, 1/(x*c+d) with its own inside staged the same way). Each group's coefficient,
//    which depends on uniforms only, becomes one prepared value. So x*a + y*b + z*c + d leaves a, b, c, d,
//    and a uniform 1/w or a factor 2 goes into the coefficients (they fold into the matrix);
//  - lifted: the expression kept as the optimizer left it, each maximal uniform-only part of a sum or a
//    product lifted into one prepared value (cheaper when the per-element part is a product of sums);
//  - kept: the per-element temporaries stay temporaries (not substituted), their uniform parts lifted. The
//    only candidate when substituting them would exceed the optimizer's size budget (paper A.1 with only
//    one parameter uniform), and never dearer per element than the unstaged program.
// Prepared values equal up to sign (by canonical key) are one value. The per-element stage and the prepare
// stage then each go through the -O2 pass pipeline (pipeline.cpp) as ordinary programs. Of the candidates
// the one with the lower per-element cost wins, then the one with fewer prepared values, then the cheaper
// prepare.
#include "opt/stage.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <stdexcept>

#include "opt/cse.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using namespace detail;

std::vector<std::string> uniform_inputs(const Kernel& k, const std::vector<std::string>& cli) {
  auto is_input = [&](const std::string& n) {
    return std::any_of(k.inputs.begin(), k.inputs.end(), [&](const KernelInput& in) { return in.name == n; });
  };
  auto is_output = [&](const std::string& n) {
    return std::any_of(k.outputs.begin(), k.outputs.end(), [&](const KernelOutput& o) { return o.name == n; });
  };
  auto why = [&](const std::string& n) {
    return is_output(n) ? "is an output; only inputs can be uniform" : "is not an input of the script";
  };
  std::set<std::string> wanted;
  for (const auto& u : k.uniforms) {
    if (is_output(u.name) || !is_input(u.name))
      throw front::CompileError(u.loc, "'#pragma uniform' names '" + u.name + "', which " + why(u.name));
    wanted.insert(u.name);
  }
  for (const auto& n : cli) {
    if (is_output(n) || !is_input(n)) {
      std::string inputs;
      for (const auto& in : k.inputs) inputs += (inputs.empty() ? "" : ", ") + in.name;
      throw std::invalid_argument("--uniform names '" + n + "', which " + why(n) + " (inputs: " +
                                  (inputs.empty() ? "none" : inputs) + ")");
    }
    wanted.insert(n);
  }
  std::vector<std::string> out;
  for (const auto& in : k.inputs)
    if (wanted.count(in.name)) out.push_back(in.name);
  return out;
}

namespace {

enum class Mode { Collect, Lift, Keep };

// One candidate split: the output roots over per-element inputs and prepared symbols, and the prepared
// values over uniform inputs and the unstaged program's uniform temporaries.
struct Split {
  std::vector<Temp> temps;  // Keep: the per-element temporaries, uniform parts lifted
  std::vector<ex> roots;
  std::vector<ex> values;
  std::vector<realsymbol> syms;
  std::vector<std::string> labels;
};

class Stager {
 public:
  Stager(Mode mode, const ExSet& element_symbols, CanonicalKeys& keys, const std::string& prefix, Split& out)
      : mode_(mode), element_(element_symbols), keys_(keys), prefix_(prefix), out_(out) {}

  ex stage(const ex& e, const std::string& label) { return mode_ == Mode::Collect ? collect(e, label) : lift(e, label); }

 private:
  bool varies(const ex& e) {
    for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (is_a<symbol>(*it) && element_.count(*it)) return true;
    return false;
  }

  // A uniform-only value as a prepared symbol (numbers stay numbers); one symbol per value up to sign. The
  // first occurrence is stored with its own sign, so a prepared value is the coefficient itself (the
  // translation column, not its negation): callers may use the prepared values as a matrix.
  ex prepared(const ex& u, const std::string& label) {
    if (is_a<numeric>(u)) return u;
    const int sign = keys_.sign(u);
    const std::string key = keys_.magnitude(u);
    auto it = index_.find(key);
    if (it == index_.end()) {
      const size_t n = out_.values.size();
      out_.syms.push_back(realsymbol(prefix_ + std::to_string(n)));
      out_.values.push_back(u);
      out_.labels.push_back(label);
      signs_.push_back(sign);
      it = index_.emplace(key, n).first;
    }
    const ex& sym = out_.syms[it->second];
    return sign == signs_[it->second] ? ex(sym) : ex(-sym);
  }

  // A label for a per-element monomial: "x", "x*y^2", "1"; anything else "f".
  static std::string monomial(const ex& m) {
    if (m.is_equal(1)) return "1";
    auto one = [](const ex& f) -> std::string {
      if (is_a<symbol>(f)) return ex_to<symbol>(f).get_name();
      if (is_a<power>(f) && is_a<symbol>(f.op(0)) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_integer())
        return ex_to<symbol>(f.op(0)).get_name() + "^" + std::to_string(ex_to<numeric>(f.op(1)).to_int());
      return "f";
    };
    if (!is_a<mul>(m)) return one(m);
    std::vector<std::string> parts;
    for (size_t i = 0; i < m.nops(); ++i) parts.push_back(one(m.op(i)));
    std::sort(parts.begin(), parts.end());
    std::string s;
    for (const auto& p : parts) s += (s.empty() ? "" : "*") + p;
    return s;
  }

  // The operands of e in the canonical order: prepared values are numbered in the order they are met, and
  // GiNaC's own operand order depends on addresses (its type hash seeds), so walking it would number them
  // differently from one process to the next.
  exvector canonical_ops(const ex& e) {
    exvector ops(e.begin(), e.end());
    std::stable_sort(ops.begin(), ops.end(), [this](const ex& a, const ex& b) { return keys_.less(a, b); });
    return ops;
  }

  // Children of e staged (per-element ones recursively, uniform ones as prepared values), in canonical order.
  ex map_children(const ex& e, const std::string& label) {
    std::map<ex, ex, ex_is_less> staged;
    for (const ex& x : canonical_ops(e))
      if (!is_a<numeric>(x) && !staged.count(x)) staged.emplace(x, varies(x) ? stage(x, label) : prepared(x, label));
    struct F : map_function {
      const std::map<ex, ex, ex_is_less>* staged;
      ex operator()(const ex& x) override { return is_a<numeric>(x) ? x : staged->at(x); }
    } f;
    f.staged = &staged;
    return e.map(f);
  }

  // One per-element factor of a collected term: x, x^2, (x*c+d)^-1, sqrt(...), sin(...).
  ex factor(const ex& f, const std::string& label) {
    if (is_a<symbol>(f)) return f;
    if (is_a<power>(f) && is_a<symbol>(f.op(0)) && is_a<numeric>(f.op(1))) return f;
    if (is_a<add>(f)) return collect(f, label);
    return map_children(f, label);
  }

  ex collect(const ex& e, const std::string& label) {
    if (!varies(e)) return prepared(e, label);
    if (is_a<symbol>(e)) return e;
    const ex x = expand(e);
    struct Group {
      ex element_part;
      exvector uniform_parts;
    };
    std::map<std::string, Group> groups;  // by the canonical key of the per-element part: a fixed order
    auto take = [&](const ex& term) {
      exvector el, un;
      if (is_a<mul>(term)) {
        for (size_t i = 0; i < term.nops(); ++i) (varies(term.op(i)) ? el : un).push_back(term.op(i));
      } else {
        (varies(term) ? el : un).push_back(term);
      }
      const ex element_part = dynallocate<mul>(el);
      Group& g = groups[keys_.key(element_part)];
      g.element_part = element_part;
      g.uniform_parts.push_back(dynallocate<mul>(un));
    };
    if (is_a<add>(x))
      for (size_t i = 0; i < x.nops(); ++i) take(x.op(i));
    else
      take(x);
    exvector terms;
    for (const auto& [key, g] : groups) {
      const ex c = prepared(dynallocate<add>(g.uniform_parts), label + "[" + monomial(g.element_part) + "]");
      exvector fs;
      if (is_a<mul>(g.element_part))
        for (const ex& f : canonical_ops(g.element_part)) fs.push_back(factor(f, label));
      else
        fs.push_back(factor(g.element_part, label));
      terms.push_back(c * dynallocate<mul>(fs));
    }
    return dynallocate<add>(terms);
  }

  ex lift(const ex& e, const std::string& label) {
    if (!varies(e)) return prepared(e, label);
    if (is_a<symbol>(e)) return e;
    if (is_a<add>(e) || is_a<mul>(e)) {
      exvector el, un;
      for (const ex& x : canonical_ops(e)) {
        if (varies(x))
          el.push_back(lift(x, label));
        else
          un.push_back(x);
      }
      if (is_a<add>(e)) return prepared(dynallocate<add>(un), label + "[1]") + dynallocate<add>(el);
      return prepared(dynallocate<mul>(un), label) * dynallocate<mul>(el);
    }
    return map_children(e, label);
  }

  Mode mode_;
  const ExSet& element_;
  CanonicalKeys& keys_;
  std::string prefix_;
  Split& out_;
  std::map<std::string, size_t> index_;  // by magnitude key
  std::vector<int> signs_;               // the sign of each stored value
};

// The temporaries the expressions need (transitively), in program order.
std::vector<Temp> needed_temps(const std::vector<Temp>& temps, const std::vector<ex>& exprs) {
  ExSet want;
  for (const auto& e : exprs) collect_symbols(e, want);
  std::vector<bool> keep(temps.size(), false);
  for (size_t i = temps.size(); i-- > 0;)
    if (want.count(temps[i].sym)) {
      keep[i] = true;
      collect_symbols(temps[i].value, want);
    }
  std::vector<Temp> out;
  for (size_t i = 0; i < temps.size(); ++i)
    if (keep[i]) out.push_back(temps[i]);
  return out;
}

// A Program with the given inputs, temporaries and output roots, put through the pass pipeline at -O2 and
// its temporaries numbered PREFIX0, PREFIX1, ... in evaluation order.
Program finish(const Program& shape, std::string name, std::vector<KernelInput> inputs, std::vector<Temp> temps,
               std::vector<ex> roots, const std::vector<ProgramOutput>& outputs, const std::string& temp_prefix) {
  Program p;
  p.name = std::move(name);
  p.algebra = shape.algebra;
  p.level = shape.level;
  p.inputs = std::move(inputs);
  if (shape.level == Level::O2) {
    CseState cse(p.inputs, temps);
    run_cse(cse, roots);
    p.temps = cse.temps;
  } else {
    p.temps = needed_temps(temps, roots);
  }
  size_t ri = 0;
  for (const auto& o : outputs) {
    ProgramOutput po{o.name, {}};
    for (const auto& s : o.slots) po.slots.push_back({s.blade, roots.at(ri++)});
    p.outputs.push_back(std::move(po));
  }
  // Temporaries renamed in evaluation order (their old names may repeat across the two stages' sources).
  Namer namer(p.inputs);
  for (size_t i = 0; i < p.temps.size(); ++i) p.temps[i].name = namer.fresh(temp_prefix + std::to_string(i));
  return p;
}

}  // namespace

namespace {
bool shape_o2(const Program& p) { return p.level == Level::O2; }
}  // namespace

StagedProgram stage(const Program& p, const std::vector<std::string>& uniforms) {
  algebra::Using in(p.algebra);
  const std::set<std::string> uniform_set(uniforms.begin(), uniforms.end());
  StagedProgram sp;
  sp.uniforms = uniforms;
  std::vector<KernelInput> uniform_inputs_, element_inputs;
  ExSet element_symbols;
  for (const auto& in : p.inputs) {
    if (uniform_set.count(in.name)) {
      uniform_inputs_.push_back(in);
    } else {
      element_inputs.push_back(in);
      element_symbols.insert(in.symbols.begin(), in.symbols.end());
    }
  }
  // The name of the prepared values' array: "prepared" unless an input has it.
  std::string prepared_name = "prepared";
  while (std::any_of(p.inputs.begin(), p.inputs.end(), [&](const KernelInput& in) {
    if (in.name == prepared_name) return true;
    return std::any_of(in.symbols.begin(), in.symbols.end(),
                       [&](const realsymbol& s) { return s.get_name().rfind(prepared_name, 0) == 0; });
  }))
    prepared_name += "_";

  // Temporaries split by rate. The size (symbol occurrences) each expression would have with the per-element
  // temporaries substituted is counted first: substituting a shared DAG into trees can explode.
  std::vector<Temp> uniform_temps, element_temp_list;
  ExSet element_or_temp = element_symbols;
  std::map<ex, double, ex_is_less> inlined_size;
  auto size_with_inlining = [&](const ex& e) {
    double n = 0;
    for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (is_a<symbol>(*it)) {
        auto f = inlined_size.find(*it);
        n += f == inlined_size.end() ? 1 : f->second;
      }
    return n;
  };
  for (const auto& t : p.temps) {
    ExSet syms;
    collect_symbols(t.value, syms);
    const bool varies =
        std::any_of(syms.begin(), syms.end(), [&](const ex& s) { return element_or_temp.count(s) > 0; });
    if (varies) {
      element_temp_list.push_back(t);
      element_or_temp.insert(t.sym);
      inlined_size[t.sym] = size_with_inlining(t.value);
    } else {
      uniform_temps.push_back(t);
    }
  }
  std::vector<ex> slot_values;
  std::vector<std::string> slot_labels;
  double inlined_total = 0;
  for (const auto& o : p.outputs)
    for (const auto& s : o.slots) {
      slot_values.push_back(s.value);
      slot_labels.push_back(o.name + "." + algebra::blade_name(s.blade));
      inlined_total += size_with_inlining(s.value);
    }
  // The same budget as the optimizer's expanded form (levels.cpp): above it only the kept form is tried.
  constexpr double kMaxInlinedSize = 4000;
  const bool inline_ok = inlined_total <= kMaxInlinedSize;
  std::vector<ex> roots;
  if (inline_ok) {
    exmap element_temps;
    for (const auto& t : element_temp_list)
      element_temps[t.sym] = element_temps.empty() ? t.value : t.value.subs(element_temps, subs_options::no_pattern);
    for (const auto& v : slot_values)
      roots.push_back(element_temps.empty() ? v : v.subs(element_temps, subs_options::no_pattern));
  }

  const SymbolNames names = symbol_names(p);
  CanonicalKeys keys(names);
  struct Candidate {
    Program prepare, body;
    long body_cost, prepare_cost;
    size_t k;
  };
  std::optional<Candidate> best;
  // Expanding a product of sums multiplies their term counts: past the -O1 inlining limit (levels.cpp's
  // kMaxInlineTerms) the collected form is not tried.
  bool collect_ok = inline_ok;
  for (const auto& r : roots) collect_ok = collect_ok && estimate_terms(r, {}) <= 4000;
  for (Mode mode : {Mode::Collect, Mode::Lift, Mode::Keep}) {
    if (mode != Mode::Keep && !inline_ok) continue;
    if (mode == Mode::Collect && !collect_ok) continue;
    Split split;
    if (mode == Mode::Keep) {
      Stager stager(Mode::Lift, element_or_temp, keys, prepared_name + "_", split);
      for (auto t : element_temp_list) {
        t.value = stager.stage(t.value, t.name);
        split.temps.push_back(t);
      }
      for (size_t i = 0; i < slot_values.size(); ++i) split.roots.push_back(stager.stage(slot_values[i], slot_labels[i]));
    } else {
      Stager stager(mode, element_symbols, keys, prepared_name + "_", split);
      for (size_t i = 0; i < roots.size(); ++i) split.roots.push_back(stager.stage(roots[i], slot_labels[i]));
    }
    if (split.values.empty())
      throw std::invalid_argument("staging: no output depends on the uniform inputs; nothing to prepare");
    KernelInput pin;
    pin.name = prepared_name;
    pin.is_multivector = true;
    pin.blades.assign(split.syms.size(), 0);
    pin.symbols = split.syms;
    std::vector<KernelInput> body_inputs{pin};
    body_inputs.insert(body_inputs.end(), element_inputs.begin(), element_inputs.end());
    Candidate c;
    c.body = finish(p, p.name, body_inputs, split.temps, split.roots, p.outputs, "t");
    c.body.labels[prepared_name] = split.labels;
    ProgramOutput prep{prepared_name, {}};
    for (size_t i = 0; i < split.values.size(); ++i) prep.slots.push_back({0, split.values[i]});
    c.prepare = finish(p, p.name + "_prepare", uniform_inputs_, uniform_temps, split.values, {prep}, "u");
    // The prepare also from scratch: the unstaged program's uniform temporaries were shared for the whole
    // kernel (per-element outputs included), which can favour other products than the prepared values
    // alone need (transform_point_split: H/w as well as G/w). So the values with those temporaries
    // substituted go through the pipeline too (not expanded: paper A.1's expansion takes minutes); the cheapest prepare is kept
    // (the first on a tie, so nothing changes where the inherited sharing is as good).
    if (shape_o2(p) && !uniform_temps.empty()) {
      exmap usubs;
      for (const auto& t : uniform_temps)
        usubs[t.sym] = usubs.empty() ? t.value : t.value.subs(usubs, subs_options::no_pattern);
      std::vector<ex> flat;
      double flat_size = 0;
      for (const auto& v : split.values) {
        flat.push_back(v.subs(usubs, subs_options::no_pattern));
        flat_size += static_cast<double>(tree_size(flat.back()));
      }
      if (flat_size <= kMaxInlinedSize) {
        Program alt = finish(p, p.name + "_prepare", uniform_inputs_, {}, flat, {prep}, "u");
        if (program_stats(alt).total.weighted() < program_stats(c.prepare).total.weighted()) c.prepare = alt;
      }
    }
    c.prepare.labels[prepared_name] = split.labels;
    c.body_cost = program_stats(c.body).total.weighted();
    c.prepare_cost = program_stats(c.prepare).total.weighted();
    c.k = split.values.size();
    if (!best || std::tie(c.body_cost, c.k, c.prepare_cost) < std::tie(best->body_cost, best->k, best->prepare_cost))
      best = std::move(c);
  }
  sp.prepare = std::move(best->prepare);
  sp.body = std::move(best->body);
  return sp;
}

std::string format_staged_stats(const StagedProgram& s) {
  const ProgramStats pre = program_stats(s.prepare), body = program_stats(s.body);
  std::string u;
  for (const auto& n : s.uniforms) u += (u.empty() ? "" : ", ") + n;
  std::string at;
  for (const auto& n : s.at) at += (at.empty() ? "" : ", ") + n;
  std::string out = "kernel " + s.body.name + " at -O" + std::to_string(static_cast<int>(s.body.level)) +
                    (at.empty() ? ", staged (uniform: " + u + ")\n" : ", staged at " + at + " (prepare reads: " + u + ")\n");
  out += "prepare: " + format_counts(pre.total) + "\n";
  out += "per element: " + format_counts(body.total) + "\n";
  out += "prepared values: " + std::to_string(s.prepare.outputs.at(0).slots.size()) + "\n";
  for (const auto& o : body.outputs) out += "output " + o.name + " (per element): " + format_counts(o.ops) + "\n";
  for (const auto& n : s.prepare.notes) out += "note: " + n + "\n";
  for (const auto& n : s.body.notes) out += "note: " + n + "\n";
  return out;
}

std::vector<EvalLine> evaluate_staged(const StagedProgram& s, const InputValues& inputs) {
  InputValues uni, el;
  for (const auto& [name, v] : inputs) {
    const bool is_uniform = std::find(s.uniforms.begin(), s.uniforms.end(), name) != s.uniforms.end();
    (is_uniform ? uni : el)[name] = v;
  }
  std::vector<double> prepared;
  for (const auto& l : evaluate(s.prepare, uni)) prepared.push_back(l.value);
  el[s.prepare.outputs.at(0).name] = prepared;
  return evaluate(s.body, el);
}

StagedCheck compare_staged(const std::vector<EvalLine>& staged, const std::vector<EvalLine>& unstaged) {
  StagedCheck c;
  if (staged.size() != unstaged.size()) return {INFINITY, false};
  for (size_t i = 0; i < staged.size(); ++i) {
    const double a = staged[i].value, b = unstaged[i].value;
    if (std::isnan(a) != std::isnan(b)) return {INFINITY, false};
    if (std::isnan(a)) continue;
    const double err = std::abs(a - b) / std::max(1.0, std::abs(b));
    c.max_rel_error = std::max(c.max_rel_error, err);
  }
  c.ok = c.max_rel_error <= 1e-9;
  return c;
}

}  // namespace cgagen::opt
