// The expander's values (expander.hpp): each assignment recorded as a KernelValue with one symbol per blade,
// parts bound to temporaries (the cost model, expand/cost.hpp; the products stage, expand/words.hpp), the
// values no output needs dropped, the outputs and multivector inputs.
#include "expand/expander.hpp"

namespace cgagen::expand_detail {

std::string Expander::unique_symbol_name(const std::string& wanted) {
  std::string n = wanted;
  for (int k = 2; symbol_names_.count(n); ++k) n = wanted + "_" + std::to_string(k);
  symbol_names_.insert(n);
  return n;
}

// One KernelValue per assignment; later statements see the name through the value's own symbols.
void Expander::record_value(const Stmt& s, const Multivector& v, bool bind) {
  int count = ++assignments_[s.name];
  KernelValue kv = value_of(s.name, count == 1 ? s.name : s.name + "_" + std::to_string(count), s.loc, v);
  if (bind) globals_[s.name] = reference(kv);  // (a macro's output does not become a global name)
  if (bind)
    for (auto* names : assigned_in_branch_) names->push_back(s.name);
  if (s.marker == front::Marker::EvalOnly) evaluated_values_.push_back(static_cast<int>(kernel_.values.size()));
  if (s.marker != front::Marker::EvalOnly) last_value_[s.name] = static_cast<int>(kernel_.values.size());
  kernel_.values.push_back(std::move(kv));
}

// A part of the current statement bound to temporaries by the cost model (expand/cost.hpp): a value of
// the kernel that no name refers to; later products see its blades' symbols.
Multivector Expander::bind_part(const Multivector& v, SourceLoc loc) {
  const std::string name = statement_name_ + "_part" + std::to_string(++parts_[statement_name_]);
  KernelValue kv = value_of(name, name, loc, v);
  Multivector ref = reference(kv);
  kernel_.values.push_back(std::move(kv));
  return ref;
}

Multivector Expander::bind_if_long(const Multivector& m, SourceLoc loc) {
  for (const auto& [b, c] : m.terms())
    if (symbolic::tree_larger_than(c, expand_cost::kBindArgumentNodes)) return bind_part(m, loc);
  return m;
}

// A product of a and b, with the operands the cost model picks bound to temporaries first.
Multivector Expander::product(algebra::ProductKind kind, Multivector a, Multivector b, SourceLoc loc) {
  const expand_cost::BindPlan plan = expand_cost::plan_product(kind, a, b);
  if (plan.a) a = bind_part(a, loc);
  if (plan.b) b = bind_part(b, loc);
  switch (kind) {
    case algebra::ProductKind::Geometric: return a * b;
    case algebra::ProductKind::Outer: return a ^ b;
    default: return inner(a, b);
  }
}

Multivector Expander::multiply(algebra::ProductKind kind, const Multivector& a, const Multivector& b, SourceLoc loc) {
  return product(kind, a, b, loc);
}

Multivector Expander::bind_word(std::string& name, const Multivector& v, SourceLoc loc) {
  if (name.empty()) name = statement_name_ + "_prod" + std::to_string(++parts_[statement_name_ + " prod"]);
  KernelValue kv = value_of(name, name, loc, v);
  Multivector ref = reference(kv);
  kernel_.values.push_back(std::move(kv));
  return ref;
}

Multivector Expander::reference(const KernelValue& kv) {
  Multivector ref;
  for (size_t i = 0; i < kv.blades.size(); ++i) ref.set(kv.blades[i], kv.symbols[i]);
  return ref;
}

// v as a kernel value: one symbol per blade whose coefficient is not identically zero.
KernelValue Expander::value_of(const std::string& name, const std::string& symbol_base, SourceLoc loc, const Multivector& v) {
  KernelValue kv;
  kv.name = name;
  kv.loc = loc;
  for (const auto& [b, c] : v.terms()) {
    // A complex constant (sqrt(-4) = 2i, log(-1) = i pi): the targets have real numbers only, and the
    // printers would drop the i (sqrt(-4)*x printed as 2*x). The emitted C would give NaN; say so here.
    // (Each shared node once: coefficients are DAGs whose trees can be exponentially large.)
    if (symbolic::has_nonreal_number(c))
      throw CompileError(loc, "the value of '" + name + "' is complex (a square root or logarithm of a "
                              "negative constant); the generated code computes with real numbers only");
    // Identically zero once earlier values are inlined? Most coefficients are plainly not, and an exact
    // probe says so at once; the others go through the float sample first (sample()).
    std::optional<ex> at_sample;
    if (!zeros_.probably_nonzero(c)) {
      at_sample = zeros_.sample(c);
      if (!at_sample) continue;
    }
    GiNaC::realsymbol sym(unique_symbol_name(symbol_base + "_" + algebra::blade_ident(b)));
    zeros_.define(sym, c, at_sample);
    kv.blades.push_back(b);
    kv.coeffs.push_back(c);
    kv.symbols.push_back(sym);
  }
  return kv;
}

// Values that no output needs (directly or through other values) are not part of the kernel: -O0 would
// emit them as dead temporaries (e.g. the inputs of a rotated point's square that cancels to 0).
void Expander::drop_unused_values() {
  std::set<ex, GiNaC::ex_is_less> needed;
  std::vector<bool> keep(kernel_.values.size(), false);
  for (const auto& o : kernel_.outputs) keep[static_cast<size_t>(o.value)] = true;
  // '!x = e;' and '#pragma onlyEvaluate x' ask for x to be evaluated: their values stay (as in Gaalop).
  for (int i : evaluated_values_) keep[static_cast<size_t>(i)] = true;
  for (size_t i = 0; i < kernel_.values.size(); ++i)
    if (pragmas_.only_evaluate(kernel_.values[i].name)) keep[i] = true;
  for (size_t i = kernel_.values.size(); i-- > 0;) {
    const KernelValue& v = kernel_.values[i];
    if (!keep[i])
      for (const auto& sym : v.symbols)
        if (needed.count(sym)) keep[i] = true;
    if (!keep[i]) continue;
    for (const auto& c : v.coeffs)
      for (auto it = c.preorder_begin(); it != c.preorder_end(); ++it)
        if (GiNaC::is_a<GiNaC::symbol>(*it)) needed.insert(*it);
  }
  std::vector<int> index(kernel_.values.size(), -1);
  std::vector<KernelValue> kept;
  for (size_t i = 0; i < kernel_.values.size(); ++i)
    if (keep[i]) {
      index[i] = static_cast<int>(kept.size());
      kept.push_back(std::move(kernel_.values[i]));
    }
  kernel_.values = std::move(kept);
  for (auto& o : kernel_.outputs) o.value = index[static_cast<size_t>(o.value)];
}

void Expander::mark(const std::string& name, SourceLoc loc) {
  for (const auto& m : marks_)
    if (m.name == name) return;
  marks_.push_back({name, loc});
}

void Expander::finish_outputs() {
  pragmas_.check_outputs([&](const std::string& name) {
    return std::any_of(marks_.begin(), marks_.end(), [&](const Mark& m) { return m.name == name; });
  });
  if (marks_.empty()) throw CompileError({1, 1}, "script has no outputs (mark one with ?name)");
  for (const auto& m : marks_) {
    auto it = last_value_.find(m.name);
    if (it == last_value_.end()) throw CompileError(m.loc, "output '" + m.name + "' is never assigned");
    KernelOutput out;
    out.name = m.name;
    out.loc = m.loc;
    out.value = it->second;
    const expand_pragmas::OutputPragma* p = pragmas_.output(m.name);
    out.from_pragma = p != nullptr;
    out.blades = p ? p->blades : kernel_.values[it->second].blades;
    if (out.blades.empty()) out.blades = {0};  // an output that is identically 0: one scalar 0, never a[0]
    kernel_.outputs.push_back(std::move(out));
  }
}

void Expander::declare_input(const std::string& name, const std::vector<algebra::BladeIndex>& blades) {
  KernelInput in;
  in.name = name;
  in.is_multivector = true;
  in.blades = blades;
  Multivector ref;
  for (auto b : blades) {
    GiNaC::realsymbol sym(unique_symbol_name(name + "_" + algebra::blade_ident(b)));
    zeros_.add_input(sym);
    in.symbols.push_back(sym);
    ref.set(b, sym);
  }
  globals_[name] = ref;
  kernel_.inputs.push_back(std::move(in));
}

}  // namespace cgagen::expand_detail
