// The oracle interpreter of the differential fuzzer (see interpreter.hpp). Every definition below is taken
// from Gaalop's documentation and macros (VecN3, RotorN3, TranslatorN3, SphereN3, Dual, abs of a
// multivector), worked out on oracle::MV in the orthonormal basis.
#include "interpreter.hpp"

#include <cmath>
#include <functional>
#include <set>

namespace diff {
namespace {

using cgagen::front::BinaryOp;
using cgagen::front::Expr;
using cgagen::front::Marker;
using cgagen::front::Stmt;
using cgagen::front::UnaryOp;

MV scalar(Real s) { return MV::scalar(s); }

bool is_scalar(const MV& m, Real tol = 1e-12) {
  Real scale = std::max(Real(1), oracle::norm1(m));
  for (unsigned i = 1; i < oracle::kBlades; ++i)
    if (std::abs(m.c[i]) > tol * scale) return false;
  return true;
}

Real as_scalar(const MV& m, const char* what) {
  if (!is_scalar(m)) throw Refused(std::string(what) + " of a non-scalar");
  return m.c[0];
}

MV vec(Real x, Real y, Real z) { return x * oracle::e1<Real>() + y * oracle::e2<Real>() + z * oracle::e3<Real>(); }

MV point(Real x, Real y, Real z) {  // Gaalop's VecN3: x + 1/2 x^2 einf + e0
  return vec(x, y, z) + (0.5 * (x * x + y * y + z * z)) * oracle::einf<Real>() + oracle::e0<Real>();
}

MV divide(const MV& a, const MV& b) {
  if (is_scalar(b)) {
    // A divisor that is zero but for rounding (t einf . t' einf) counts as zero, as the exact pipeline has it.
    if (std::abs(b.c[0]) < Real(1e-13)) throw Refused("division by zero");
    return a / b.c[0];
  }
  const MV n = b * oracle::reverse(b);
  if (!is_scalar(n, 1e-9)) throw Refused("division by a non-versor");
  if (std::abs(n.c[0]) < 1e-12 * std::max(Real(1), oracle::norm1(b) * oracle::norm1(b))) throw Refused("null divisor");
  return a * oracle::reverse(b) / n.c[0];
}

MV magnitude(const MV& m) { return scalar(std::sqrt(std::abs(oracle::scalar_part(m * oracle::reverse(m))))); }

// exp of a scalar, or of a bivector whose square is a scalar (closed forms, as Gaalop's exp is defined only
// there); anything else is refused.
MV exponential(const MV& b) {
  if (is_scalar(b)) return scalar(std::exp(b.c[0]));
  for (unsigned i = 0; i < oracle::kBlades; ++i)
    if (oracle::grade_of(i) != 2 && std::abs(b.c[i]) > 1e-12 * std::max(Real(1), oracle::norm1(b))) throw Refused("exp of a non-bivector");
  const MV sq = b * b;
  if (!is_scalar(sq, 1e-9)) throw Refused("exp of a bivector whose square is not a scalar");
  const Real s = sq.c[0];
  if (std::abs(s) < Real(1e-300)) return scalar(1) + b;
  if (s < 0) {
    const Real t = std::sqrt(-s);
    return scalar(std::cos(t)) + (std::sin(t) / t) * b;
  }
  const Real t = std::sqrt(s);
  return scalar(std::cosh(t)) + (std::sinh(t) / t) * b;
}

class Interp {
 public:
  explicit Interp(const std::map<std::string, double>& inputs) : inputs_(inputs) {}

  Outputs run(const cgagen::front::Script& script) {
    for (const auto& s : script.statements)
      if (s->kind == Stmt::Kind::Assign) top_names_.insert(s->name);
    std::vector<std::pair<std::string, bool>> in_branches;
    for (const auto& s : script.statements)
      if (s->kind == Stmt::Kind::If) assigned({s}, in_branches);
    for (const auto& [n, output] : in_branches) top_names_.insert(n);
    taken_ = top_names_;
    for (const auto& [n, v] : inputs_) taken_.insert(n);
    for (const auto& s : script.statements) top(*s);
    Outputs out;
    for (const auto& n : marks_) {
      auto it = globals_.find(n);
      if (it == globals_.end()) throw Refused("output never assigned: " + n);
      out.order.push_back(n);
      out.values[n] = it->second;
    }
    return out;
  }

 private:
  struct Frame {
    std::vector<MV> args;
    std::map<std::string, MV> locals;
    std::map<std::string, std::string> inlined;  // each local's name in this call
  };

  // Gaalop's Inliner: local k of macro M becomes macro_M_k in a call, or macro_M_kN with the smallest N >= 1
  // where that name is taken (by the script or an earlier call). Once per call and local.
  std::string inlined_name(const std::string& macro, const std::string& local) {
    auto& named = frames_.back().inlined;
    auto known = named.find(local);
    if (known != named.end()) return known->second;
    std::string n = "macro_" + macro + "_" + local;
    for (int k = 1; taken_.count(n); ++k) n = "macro_" + macro + "_" + local + std::to_string(k);
    taken_.insert(n);
    return named[local] = n;
  }

  void mark(const std::string& n) {
    for (const auto& m : marks_)
      if (m == n) return;
    marks_.push_back(n);
  }

  void top(const Stmt& s) {
    switch (s.kind) {
      case Stmt::Kind::Pragma:
        // '#pragma input M 1 e1^e2 ...': M is the sum of the inputs "M[k]" times the k-th declared blade.
        // Other pragmas (output, range, ...) change no value.
        if (s.words.size() >= 3 && s.words[0] == "input") mv_inputs_[s.words[1]] = {s.words.begin() + 2, s.words.end()};
        return;
      case Stmt::Kind::MacroDef: macros_[s.name][arity(s)] = &s; latest_[s.name] = &s; return;
      case Stmt::Kind::ExprStmt: eval(*s.value); return;
      case Stmt::Kind::If: branch(s); return;
      case Stmt::Kind::Assign: break;
    }
    if (s.value) globals_[s.name] = eval(*s.value);
    if (s.marker == Marker::Output || s.marker == Marker::Visual) mark(s.name);
  }

  // if/else as a program runs it: the condition decides which branch runs (the other is evaluated too, for
  // its refusals, then forgotten). As cgagen defines it
  // (docs/language.md): a name that only the branch not taken assigns and that had no value before is 0
  // after the 'if', and the outputs either branch marks are outputs.
  void branch(const Stmt& s) {
    const bool taken = holds(*s.value);
    {
      // cgagen expands both branches, so it refuses a branch that cannot be evaluated (exp of a multivector
      // that is not a bivector) even where it never runs: run the other branch too, for its refusals only.
      const auto globals = globals_;
      const auto marks = marks_;
      for (const auto& st : taken ? s.else_body : s.body) top(*st);
      globals_ = globals;
      marks_ = marks;
    }
    for (const auto& st : taken ? s.body : s.else_body) top(*st);
    std::vector<std::pair<std::string, bool>> names;  // name, marked as an output
    assigned(s.body, names);
    assigned(s.else_body, names);
    for (const auto& [n, output] : names) {
      if (!globals_.count(n)) globals_[n] = MV();
      if (output) mark(n);
    }
  }

  static void assigned(const std::vector<cgagen::front::StmtPtr>& body, std::vector<std::pair<std::string, bool>>& out) {
    for (const auto& st : body) {
      if (st->kind == Stmt::Kind::If) {
        assigned(st->body, out);
        assigned(st->else_body, out);
      } else if (st->kind == Stmt::Kind::Assign && st->value) {
        out.push_back({st->name, st->marker == Marker::Output || st->marker == Marker::Visual});
      }
    }
  }

  bool holds(const Expr& c) {
    if (c.kind == Expr::Kind::Logic) {
      if (c.text == "!") return !holds(*c.args[0]);
      if (c.text == "&&") return holds(*c.args[0]) && holds(*c.args[1]);
      return holds(*c.args[0]) || holds(*c.args[1]);
    }
    if (c.kind != Expr::Kind::Compare) return as_scalar(eval(c), "an if condition") != 0;
    const Real a = as_scalar(eval(*c.args[0]), "a comparison"), b = as_scalar(eval(*c.args[1]), "a comparison");
    if (c.text == "<") return a < b;
    if (c.text == "<=") return a <= b;
    if (c.text == ">") return a > b;
    if (c.text == ">=") return a >= b;
    if (c.text == "==") return a == b;
    return a != b;
  }

  static size_t arity(const Stmt& def) {
    size_t n = 0;
    std::function<void(const Expr&)> walk = [&](const Expr& x) {
      if (x.kind == Expr::Kind::MacroArg) n = std::max(n, static_cast<size_t>(x.index));
      for (const auto& a : x.args) walk(*a);
    };
    for (const auto& st : def.body)
      if (st->value) walk(*st->value);
    if (def.result) walk(*def.result);
    return n;
  }

  MV name(const std::string& n) {
    if (n == "e1") return oracle::e1<Real>();
    if (n == "e2") return oracle::e2<Real>();
    if (n == "e3") return oracle::e3<Real>();
    if (n == "einf") return oracle::einf<Real>();
    if (n == "e0") return oracle::e0<Real>();
    if (!frames_.empty()) {
      auto it = frames_.back().locals.find(n);
      if (it != frames_.back().locals.end()) return it->second;
    }
    auto g = globals_.find(n);
    if (g != globals_.end()) return g->second;
    auto mv = mv_inputs_.find(n);
    if (mv != mv_inputs_.end()) {
      MV sum;
      for (size_t k = 0; k < mv->second.size(); ++k) {
        auto c = inputs_.find(n + "[" + std::to_string(k) + "]");
        if (c == inputs_.end()) throw Refused("no value for input " + n + "[" + std::to_string(k) + "]");
        sum += static_cast<Real>(c->second) * oracle::null_blade<Real>(mv->second[k]);
      }
      return sum;
    }
    auto in = inputs_.find(n);
    if (in == inputs_.end()) throw Refused("no value for input " + n);
    return scalar(static_cast<Real>(in->second));
  }

  MV eval(const Expr& e) {
    switch (e.kind) {
      case Expr::Kind::Number: return scalar(std::stold(e.text));
      case Expr::Kind::Name: return name(e.text);
      case Expr::Kind::MacroArg: return frames_.back().args.at(static_cast<size_t>(e.index - 1));
      case Expr::Kind::Unary: {
        MV a = eval(*e.args[0]);
        if (e.unary_op == UnaryOp::Negate) return -a;
        if (e.unary_op == UnaryOp::Reverse) return oracle::reverse(a);
        return oracle::dual(a);
      }
      case Expr::Kind::Binary: {
        MV a = eval(*e.args[0]), b = eval(*e.args[1]);
        switch (e.binary_op) {
          case BinaryOp::Add: return a + b;
          case BinaryOp::Sub: return a - b;
          case BinaryOp::Geo: return a * b;
          case BinaryOp::Outer: return a ^ b;
          case BinaryOp::Inner: return oracle::inner(a, b);
          case BinaryOp::Div: return divide(a, b);
        }
        break;
      }
      case Expr::Kind::Call: return call(e);
      case Expr::Kind::Compare:
      case Expr::Kind::Logic: throw Refused("a condition outside an if");
    }
    throw Refused("unknown expression");
  }

  MV call(const Expr& e) {
    std::vector<MV> a;
    for (const auto& x : e.args) a.push_back(eval(*x));
    const std::string& f = e.text;
    auto m = macros_.find(f);
    if (m != macros_.end()) {
      auto d = m->second.find(a.size());
      const Stmt* def = d != m->second.end() ? d->second : latest_.at(f);
      frames_.push_back({a, {}, {}});
      // Every local of the call is renamed, an output or not: each takes its name (Gaalop numbers them so).
      for (const auto& st : def->body)
        if (st->kind == Stmt::Kind::Assign && st->value) inlined_name(f, st->name);
      for (const auto& st : def->body) {
        if (st->kind != Stmt::Kind::Assign || !st->value) continue;
        frames_.back().locals[st->name] = eval(*st->value);
        if (st->marker == Marker::Output || st->marker == Marker::Visual) {
          // Gaalop: a '?k' inside a macro is an output, named as the inliner renames the call's local.
          const std::string n = inlined_name(f, st->name);
          globals_[n] = frames_.back().locals[st->name];
          mark(n);
        }
      }
      MV r = def->result ? eval(*def->result) : MV{};
      frames_.pop_back();
      return r;
    }
    auto s = [&](size_t i) { return as_scalar(a.at(i), f.c_str()); };
    if (f == "abs") return is_scalar(a.at(0)) ? scalar(std::abs(a[0].c[0])) : magnitude(a[0]);
    if (f == "sqrt") return scalar(std::sqrt(s(0)));
    if (f == "sin") return scalar(std::sin(s(0)));
    if (f == "cos") return scalar(std::cos(s(0)));
    if (f == "tan") return scalar(std::tan(s(0)));
    if (f == "atan") return scalar(std::atan(s(0)));
    if (f == "atan2") return scalar(std::atan2(s(0), s(1)));
    if (f == "log") return scalar(std::log(s(0)));
    if (f == "floor") return scalar(std::floor(s(0)));
    if (f == "ceil") return scalar(std::ceil(s(0)));
    if (f == "exp") return exponential(a.at(0));
    if (f == "VecN3" || f == "createPoint") return point(s(0), s(1), s(2));
    // Gaalop's SphereN3 is the dual of the vector sphere P - r^2/2 einf.
    if (f == "SphereN3" && a.size() == 4)
      return oracle::dual(point(s(0), s(1), s(2)) - (0.5 * s(3) * s(3)) * oracle::einf<Real>());
    if (f == "SphereN3") return oracle::dual(a[0] - (0.5 * s(1) * s(1)) * oracle::einf<Real>());
    if (f == "TranslatorN3") return scalar(1) - 0.5 * (vec(s(0), s(1), s(2)) * oracle::einf<Real>());
    if (f == "RotorN3") {
      const Real x = s(0), y = s(1), z = s(2), phi = s(3);
      const MV e12 = oracle::e1<Real>() * oracle::e2<Real>(), e13 = oracle::e1<Real>() * oracle::e3<Real>(),
               e23 = oracle::e2<Real>() * oracle::e3<Real>();
      return scalar(std::cos(phi / 2)) + (std::sin(phi / 2) / std::sqrt(x * x + y * y + z * z)) * (-x * e23 + y * e13 - z * e12);
    }
    if (f == "Dual") return oracle::dual(a.at(0));
    if (f == "invert") return divide(scalar(1), a.at(0));
    if (f == "Normalize") return divide(Real(-1) * a.at(0), oracle::inner(a[0], oracle::einf<Real>()));  // Gaalop's CGA macro
    if (f == "coefficient") {
      // the blade argument is one null-basis blade times +-1: find it
      const MV& blade = a.at(1);
      const auto& names = oracle::null_blade_names();
      const auto coeffs = oracle::to_null_basis(blade);
      int found = -1;
      for (unsigned k = 0; k < oracle::kBlades; ++k)
        if (std::abs(coeffs[k]) > 1e-12) {
          if (found >= 0) throw Refused("coefficient of a non-blade");
          found = static_cast<int>(k);
        }
      if (found < 0) throw Refused("coefficient of 0");
      return scalar(oracle::to_null_basis(a[0])[static_cast<unsigned>(found)] / coeffs[static_cast<unsigned>(found)]);
      (void)names;
    }
    throw Refused("unknown function " + f);
  }

  const std::map<std::string, double>& inputs_;
  std::map<std::string, std::vector<std::string>> mv_inputs_;  // '#pragma input' name -> its blades
  std::map<std::string, MV> globals_;
  std::map<std::string, std::map<size_t, const Stmt*>> macros_;
  std::map<std::string, const Stmt*> latest_;
  std::vector<Frame> frames_;
  std::vector<std::string> marks_;
  std::set<std::string> top_names_;
  std::set<std::string> taken_;  // the names a call's macro_M_k must differ from
};

}  // namespace

Outputs interpret(const cgagen::front::Script& script, const std::map<std::string, double>& inputs) {
  return Interp(inputs).run(script);
}

}  // namespace diff
