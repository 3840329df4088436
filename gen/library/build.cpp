// Library kernels (build.hpp): one script per operation and operand types, expanded and optimized as any
// script is, its output given the blades of the smallest type that holds its support.
#include "library/build.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "symbolic/node_cache.hpp"

namespace cgagen::library {

namespace {

std::string blade_words(const algebra::Algebra& alg, const std::vector<algebra::BladeIndex>& blades) {
  std::string s;
  for (algebra::BladeIndex b : blades) s += " " + (b == 0 ? std::string("1") : alg.blade_name(b));
  return s;
}

std::vector<int> grades_of(const algebra::Algebra& alg, const std::vector<algebra::BladeIndex>& blades) {
  std::set<int> g;
  for (algebra::BladeIndex b : blades) g.insert(alg.grade(b));
  return {g.begin(), g.end()};
}

// True when <a ~a>_0 of type t is never positive (every term of its polynomial negative: CGA's flat points,
// whose <F ~F>_0 is -w^2 for the einf^e0 coefficient w): such a versor is normalized to <a ~a>_0 = -1, and its inverse is -~a.
bool negative_norm(const Type& t, const algebra::Algebra& alg) {
  const std::string script = "#pragma input a" + blade_words(alg, t.blades) + "\n?q = rnorm_sqr(a);\n";
  front::SourceFile file("norm.clu", script);
  const Kernel k = expand(front::parse(file), "norm", nullptr);
  const KernelValue& v = k.values.at(k.outputs.at(0).value);
  if (v.coeffs.empty()) return false;
  const GiNaC::ex q = v.coeffs.at(0).expand();
  GiNaC::exmap ones;
  for (const KernelInput& in : k.inputs)
    for (const auto& sym : in.symbols) ones[sym] = 1;
  auto negative = [&](const GiNaC::ex& term) {
    const GiNaC::ex c = term.subs(ones);
    return GiNaC::is_a<GiNaC::numeric>(c) && GiNaC::ex_to<GiNaC::numeric>(c).is_negative();
  };
  if (!GiNaC::is_a<GiNaC::add>(q)) return negative(q);
  for (size_t i = 0; i < q.nops(); ++i)
    if (!negative(q.op(i))) return false;
  return true;
}

// The sandwich's rules for a versor a of type t: a b ~a with `#pragma normalized a` (a ~a = 1), or -a b ~a
// for a type whose <a ~a>_0 is never positive (normalized to -1). Returns the pragma lines and the wrapper of
// the product's text.
std::pair<std::string, std::string> sandwich_rule(const Type& t, const algebra::Algebra& alg) {
  if (negative_norm(t, alg)) return {"", "-(%)"};
  return {"#pragma normalized a\n", "%"};
}

std::string wrap(const std::string& pattern, const std::string& text) {
  const size_t at = pattern.find('%');
  return pattern.substr(0, at) + text + pattern.substr(at + 1);
}

// " grade(m, g1) + grade(m, g2) ..." over the grades of type t's blades.
std::string grades_text(const std::string& m, const Type& t, const algebra::Algebra& alg) {
  const std::vector<int> g = grades_of(alg, t.blades);
  std::string s;
  for (size_t i = 0; i < g.size(); ++i) s += std::string(i ? " +" : "") + " grade(" + m + ", " + std::to_string(g[i]) + ")";
  return s;
}

}  // namespace

std::string operation_script(const Operation& op, const Type& a, const Type* b, const algebra::Algebra& alg) {
  std::string s = "#pragma input a" + blade_words(alg, a.blades) + "\n";
  if (b) s += "#pragma input b" + blade_words(alg, b->blades) + "\n";
  if (!op.sandwich) return s + "?r = " + op.expression + ";\n";
  // Versor application keeps grades: the result is the grades of b's type, of a b a^-1 for a normalized a.
  const auto [pragma, pattern] = sandwich_rule(a, alg);
  return s + pragma + "m = " + wrap(pattern, op.expression) + ";\n?r =" + grades_text("m", *b, alg) + ";\n";
}

std::string matrix_script(const Type& a, const Type& b, const algebra::Algebra& alg) {
  const auto [pragma, pattern] = sandwich_rule(a, alg);
  std::string s = "#pragma input a" + blade_words(alg, a.blades) + "\n" + pragma;
  for (size_t j = 0; j < b.blades.size(); ++j) {
    const std::string m = "m" + std::to_string(j);
    const std::string blade = b.blades[j] == 0 ? "1" : alg.blade_name(b.blades[j]);
    s += m + " = " + wrap(pattern, "a * (" + blade + ") * ~a") + ";\n?c" + std::to_string(j) + " =" + grades_text(m, b, alg) + ";\n";
  }
  return s;
}

size_t result_type(Library& lib, const std::vector<algebra::BladeIndex>& support) {
  size_t best = lib.types.size();
  for (size_t t = 0; t < lib.declared; ++t) {
    const auto& bl = lib.types[t].blades;
    const bool holds = std::all_of(support.begin(), support.end(),
                                   [&](algebra::BladeIndex x) { return std::find(bl.begin(), bl.end(), x) != bl.end(); });
    if (holds && (best == lib.types.size() || bl.size() < lib.types[best].blades.size())) best = t;
  }
  if (best < lib.types.size()) return best;
  std::vector<algebra::BladeIndex> sorted = support;
  std::sort(sorted.begin(), sorted.end());
  for (size_t t = lib.declared; t < lib.types.size(); ++t)
    if (lib.types[t].blades == sorted) return t;
  unsigned long long mask = 0;
  for (algebra::BladeIndex x : sorted) mask |= 1ull << lib.algebra_ptr->bits(x);
  char hex[32];
  std::snprintf(hex, sizeof hex, "mv_%llx", mask);
  lib.types.push_back(Type{hex, sorted, {}, false});
  return lib.types.size() - 1;
}

Library build(const Spec& spec, opt::Level level) {
  Library lib;
  lib.name = spec.name;
  lib.algebra = spec.algebra_spelling;
  lib.algebra_ptr = spec.algebra;
  lib.aliases = spec.aliases;
  algebra::Using use(spec.algebra);
  lib.types.push_back(Type{kScalarType, {0}, {}, true});
  for (const Type& t : spec.types) lib.types.push_back(t);
  lib.declared = lib.types.size();
  std::set<std::string> kernel_names;
  for (const Operation& op : operations()) {
    // Operands: the spec's types (not the scalar: scaling is the wrappers' generic code).
    for (size_t a = 1; a < lib.declared; ++a)
      for (size_t b = op.arity == 2 ? 1 : 0; b < (op.arity == 2 ? lib.declared : 1); ++b) {
        const Type& ta = lib.types[a];
        const Type* tb = op.arity == 2 ? &lib.types[b] : nullptr;
        std::string name = std::string(op.name) + "_" + ta.name + (tb ? "_" + tb->name : "");
        for (int k = 2; !kernel_names.insert(name).second; ++k) name += "_" + std::to_string(k);
        if (op.needs_scalar && std::find(ta.blades.begin(), ta.blades.end(), 0) == ta.blades.end()) {
          lib.skipped.push_back({&op, a, b, "takes a type with the scalar blade (a rotor, boost or motor)"});
          continue;
        }
        const std::string script = operation_script(op, ta, tb, *spec.algebra);
        symbolic::NodeCacheScope caches;
        Kernel kernel;
        try {
          front::SourceFile file(name + ".clu", script);
          kernel = expand(front::parse(file), name, spec.algebra);
        } catch (const front::CompileError& e) {
          lib.skipped.push_back({&op, a, b, e.what()});
          continue;
        }
        KernelOutput& out = kernel.outputs.at(0);
        const std::vector<algebra::BladeIndex> support = kernel.values.at(out.value).blades;
        if (support.empty()) {
          lib.skipped.push_back({&op, a, b, "the result is 0 for every value of the operands"});
          continue;
        }
        const size_t r = result_type(lib, support);
        out.blades = lib.types[r].blades;
        out.from_pragma = true;
        try {
          lib.functions.push_back({&op, a, b, r, opt::optimize(kernel, level)});
        } catch (const front::CompileError& e) {
          lib.skipped.push_back({&op, a, b, e.what()});
        }
      }
  }
  for (size_t i = 0; i < lib.functions.size(); ++i) {
    const Function& f = lib.functions[i];
    const Type& ta = lib.types[f.a];
    if (!f.op->sandwich || std::find(ta.blades.begin(), ta.blades.end(), 0) == ta.blades.end()) continue;
    std::string name = "matrix_" + ta.name + "_" + lib.types[f.b].name;
    for (int k = 2; !kernel_names.insert(name).second; ++k) name += "_" + std::to_string(k);
    symbolic::NodeCacheScope caches;
    front::SourceFile file(name + ".clu", matrix_script(ta, lib.types[f.b], *spec.algebra));
    Kernel kernel = expand(front::parse(file), name, spec.algebra);
    for (KernelOutput& out : kernel.outputs) {  // every column in the sandwich's result type
      out.blades = lib.types[f.result].blades;
      out.from_pragma = true;
    }
    lib.matrices.push_back({f.a, f.b, f.result, i, opt::optimize(kernel, level)});
  }
  return lib;
}

}  // namespace cgagen::library
