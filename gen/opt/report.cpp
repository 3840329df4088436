// --stats text, double-precision evaluation, line diffs (see report.hpp).
#include "opt/report.hpp"

#include "opt/passes.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "symbolic/select.hpp"

namespace cgagen::opt {

using namespace GiNaC;

std::string format_counts(const OpCounts& c) {
  return std::to_string(c.add) + " add, " + std::to_string(c.mul) + " mul, " + std::to_string(c.div) + " div, " +
         std::to_string(c.call) + " call";
}

std::string format_stats(const Program& p) {
  ProgramStats st = program_stats(p);
  std::string s = "kernel " + p.name + " at -O" + std::to_string(static_cast<int>(p.level)) + "\n";
  for (const auto& o : st.outputs) s += "output " + o.name + ": " + format_counts(o.ops) + "\n";
  s += "temporaries (" + std::to_string(st.temp_count) + "): " + format_counts(st.temps) + "\n";
  s += "total: " + format_counts(st.total) + "\n";
  for (const auto& n : p.notes) s += "note: " + n + "\n";
  return s;
}

std::string format_passes(const Program& p) {
  if (p.level != Level::O2) return "";
  std::string s = "passes:";
  for (const auto& pass : pass_table()) s += " " + pass.name;
  return s + "\n";
}

std::string format_products(const Kernel& k) {
  std::string s;
  for (const auto& sp : k.shared_products)
    s += "product " + sp.name + " = " + sp.word + ": " + (sp.bound ? "bound once" : "the script's value") + ", " +
         std::to_string(sp.uses) + (sp.uses == 1 ? " reuse" : " reuses") + "\n";
  return s;
}

std::string format_inputs(const Program& p) {
  algebra::Using in(p.algebra);
  std::string s = "inputs:";
  if (p.inputs.empty()) s += " (none)";
  for (size_t i = 0; i < p.inputs.size(); ++i) {
    const KernelInput& in = p.inputs[i];
    s += (i ? ", " : " ") + in.name;
    if (!in.is_multivector) continue;
    s += " (";
    const auto labels = p.labels.find(in.name);  // a staged kernel's prepared values are not blades
    for (size_t b = 0; b < in.blades.size(); ++b)
      s += (b ? ", " : "") + (labels != p.labels.end() ? labels->second.at(b) : algebra::blade_name(in.blades[b]));
    s += ")";
  }
  return s + "\n";
}

namespace {

// Evaluates expressions in double precision in exactly the order the emitters print them (opt/lower.hpp:
// sums in sum_terms order with negative terms subtracted, products left to right as c * f1 * f2 ... over
// d1 * d2 ..., powers spelled out), so --eval gives the bits the emitted C++ gives, in every process.
class Evaluator {
 public:
  explicit Evaluator(CanonicalKeys& keys) : keys_(keys) {}
  void bind(const ex& sym, double v) { env_[sym] = v; }

  double eval(const ex& e) {
    if (is_a<numeric>(e)) return real(ex_to<numeric>(e));
    if (is_a<symbol>(e)) {
      auto it = env_.find(e);
      if (it == env_.end()) throw std::logic_error("evaluate: unbound symbol " + ex_to<symbol>(e).get_name());
      return it->second;
    }
    if (is_a<constant>(e)) return real(ex_to<numeric>(e.evalf()));
    if (is_a<add>(e)) {
      double s = 0;
      bool first = true;
      for (const ex& t : sum_terms(e, keys_)) {
        const bool neg = is_negative_term(t, keys_);
        const double a = eval(neg ? ex(-t) : t);
        s = first ? (neg ? -a : a) : (neg ? s - a : s + a);
        first = false;
      }
      return s;
    }
    return product(e);
  }

 private:
  static double real(const numeric& n) {
    if (!n.is_real()) throw std::runtime_error("complex constant in a kernel expression");
    return n.to_double();
  }

  double product(const ex& e) {
    const ProductParts p = split_product(e, keys_);
    const numeric c = abs(p.coeff);
    double num = 0, den = 1;
    bool any = false;
    auto times = [&](double& acc, bool& started, double v) {
      acc = started ? acc * v : v;
      started = true;
    };
    if (c != 1 || p.num.empty()) times(num, any, real(c));
    for (const auto& f : p.num) {
      const double a = atom(f.base);
      for (int k = 0; k < f.exponent; ++k) times(num, any, a);
    }
    bool any_den = false;
    for (const auto& f : p.den) {
      const double a = atom(f.base);
      for (int k = 0; k < f.exponent; ++k) times(den, any_den, a);
    }
    const double r = any_den ? num / den : num;
    return p.coeff.is_negative() ? -r : r;
  }

  double atom(const ex& b) {
    if (is_a<symbol>(b) || is_a<numeric>(b) || is_a<constant>(b) || is_a<add>(b) || is_a<mul>(b)) return eval(b);
    if (is_sqrt(b)) return std::sqrt(eval(b.op(0)));
    if (is_a<power>(b)) return std::pow(eval(b.op(0)), eval(b.op(1)));
    if (symbolic::is_select(b)) {  // printed c ? x : y: only the chosen branch is evaluated
      const bool holds = symbolic::select_holds(symbolic::select_operator(b), eval(b.op(0)), eval(b.op(1)));
      return eval(b.op(holds ? 2 : 3));
    }
    if (is_a<function>(b)) {
      std::string f = ex_to<function>(b).get_name();
      std::vector<double> a;
      for (size_t i = 0; i < b.nops(); ++i) a.push_back(eval(b.op(i)));
      if (f == "sin") return std::sin(a.at(0));
      if (f == "cos") return std::cos(a.at(0));
      if (f == "tan") return std::tan(a.at(0));
      if (f == "asin") return std::asin(a.at(0));
      if (f == "acos") return std::acos(a.at(0));
      if (f == "atan") return std::atan(a.at(0));
      if (f == "atan2") return std::atan2(a.at(0), a.at(1));
      if (f == "exp") return std::exp(a.at(0));
      if (f == "log") return std::log(a.at(0));
      if (f == "abs") return std::abs(a.at(0));
      if (f == "sinh") return std::sinh(a.at(0));
      if (f == "cosh") return std::cosh(a.at(0));
      if (f == "tanh") return std::tanh(a.at(0));
      throw std::runtime_error("evaluate: unsupported function " + f);
    }
    throw std::runtime_error("evaluate: unsupported expression");
  }

  CanonicalKeys& keys_;
  std::map<ex, double, ex_is_less> env_;
};

}  // namespace

std::vector<EvalLine> evaluate(const Program& p, const InputValues& inputs) {
  algebra::Using in(p.algebra);
  const SymbolNames names = symbol_names(p);
  CanonicalKeys keys(names);
  Evaluator ev(keys);
  for (const auto& [name, vals] : inputs) {
    bool known = false;
    for (const auto& in : p.inputs) known |= in.name == name;
    if (!known) throw std::invalid_argument("--eval: '" + name + "' is not an input of " + p.name);
  }
  for (const auto& in : p.inputs) {
    auto it = inputs.find(in.name);
    if (it == inputs.end()) throw std::invalid_argument("--eval: no value for input '" + in.name + "'");
    if (it->second.size() != in.symbols.size())
      throw std::invalid_argument("--eval: input '" + in.name + "' needs " + std::to_string(in.symbols.size()) +
                                  " value(s), got " + std::to_string(it->second.size()));
    for (size_t k = 0; k < in.symbols.size(); ++k) ev.bind(in.symbols[k], it->second[k]);
  }
  for (const auto& t : p.temps) ev.bind(t.sym, ev.eval(t.value));
  std::vector<EvalLine> out;
  for (const auto& o : p.outputs)
    for (const auto& s : o.slots) out.push_back({o.name, s.blade, algebra::blade_name(s.blade), ev.eval(s.value)});
  return out;
}

std::string format_eval(const std::vector<EvalLine>& lines) {
  std::string s;
  char buf[64];
  for (const auto& l : lines) {
    // -0 prints as 0: the sign of a zero depends on GiNaC's term order, which varies between processes.
    // A NaN prints as nan: its sign bit is as arbitrary as a zero's (printf would say -nan for some).
    if (std::isnan(l.value)) std::snprintf(buf, sizeof buf, "nan");
    else std::snprintf(buf, sizeof buf, "%.17g", l.value == 0.0 ? 0.0 : l.value);
    s += l.output + " " + l.blade_name + " " + buf + "\n";
  }
  return s;
}

namespace {

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> lines;
  std::istringstream in(s);
  std::string l;
  while (std::getline(in, l)) lines.push_back(l);
  return lines;
}

}  // namespace

std::string unified_diff(const std::string& a, const std::string& b, const std::string& name_a,
                         const std::string& name_b) {
  if (a == b) return "";
  auto A = split_lines(a), B = split_lines(b);
  const size_t n = A.size(), m = B.size();
  // LCS table from the end: lcs[i][j] = LCS length of A[i..], B[j..].
  std::vector<std::vector<int>> lcs(n + 1, std::vector<int>(m + 1, 0));
  for (size_t i = n; i-- > 0;)
    for (size_t j = m; j-- > 0;)
      lcs[i][j] = A[i] == B[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);
  struct Op {
    char kind;  // ' ', '-', '+'
    size_t ia, ib;
  };
  std::vector<Op> ops;
  size_t i = 0, j = 0;
  while (i < n || j < m) {
    if (i < n && j < m && A[i] == B[j]) ops.push_back({' ', i++, j++});
    // Deletions before insertions where both keep the LCS, as diff(1) prints a changed line.
    else if (i < n && (j == m || lcs[i + 1][j] >= lcs[i][j + 1])) ops.push_back({'-', i++, j});
    else ops.push_back({'+', i, j++});
  }
  std::string out = "--- " + name_a + "\n+++ " + name_b + "\n";
  const size_t ctx = 3;
  size_t k = 0;
  while (k < ops.size()) {
    if (ops[k].kind == ' ') {
      ++k;
      continue;
    }
    size_t start = k >= ctx ? k - ctx : 0;
    size_t end = k;
    // Extend the hunk while changes are within 2*ctx of each other.
    size_t last_change = k;
    for (size_t q = k; q < ops.size(); ++q) {
      if (ops[q].kind != ' ') last_change = q;
      else if (q - last_change > 2 * ctx) break;
      end = q;
    }
    end = std::min(ops.size() - 1, last_change + ctx);
    size_t a0 = ops[start].ia, b0 = ops[start].ib, na = 0, nb = 0;
    for (size_t q = start; q <= end; ++q) {
      if (ops[q].kind != '+') ++na;
      if (ops[q].kind != '-') ++nb;
    }
    out += "@@ -" + std::to_string(a0 + 1) + "," + std::to_string(na) + " +" + std::to_string(b0 + 1) + "," +
           std::to_string(nb) + " @@\n";
    for (size_t q = start; q <= end; ++q)
      out += std::string(1, ops[q].kind) + (ops[q].kind == '+' ? B[ops[q].ib] : A[ops[q].ia]) + "\n";
    k = end + 1;
  }
  return out;
}

std::string stats_delta(const Program& a, const Program& b) {
  ProgramStats sa = program_stats(a), sb = program_stats(b);
  auto delta = [](const OpCounts& x, const OpCounts& y) {
    auto d = [](long u, long v) {
      long dd = v - u;
      return std::to_string(u) + " -> " + std::to_string(v) + " (" + (dd > 0 ? "+" : "") + std::to_string(dd) + ")";
    };
    return "add " + d(x.add, y.add) + ", mul " + d(x.mul, y.mul) + ", div " + d(x.div, y.div) + ", call " +
           d(x.call, y.call);
  };
  std::string la = "-O" + std::to_string(static_cast<int>(a.level)), lb = "-O" + std::to_string(static_cast<int>(b.level));
  std::string s = "op counts " + la + " -> " + lb + ":\n";
  for (size_t i = 0; i < sa.outputs.size() && i < sb.outputs.size(); ++i)
    s += "  output " + sa.outputs[i].name + ": " + delta(sa.outputs[i].ops, sb.outputs[i].ops) + "\n";
  s += "  temporaries: " + std::to_string(sa.temp_count) + " -> " + std::to_string(sb.temp_count) + "\n";
  s += "  total: " + delta(sa.total, sb.total) + "\n";
  return s;
}

}  // namespace cgagen::opt
