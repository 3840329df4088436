// The expander's expressions (expander.hpp): numbers, basis vectors, names and free names as inputs,
// operators, product chains as words (expand/words.hpp), division.
#include "expand/expander.hpp"

namespace cgagen::expand_detail {

// "0.5" -> 1/2, "1e-3" -> 1/1000, "12" -> 12, exactly.
std::optional<ex> parse_number(const std::string& text) {
  std::string digits;
  int frac = 0;
  size_t i = 0;
  bool dot = false, any = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (c >= '0' && c <= '9') {
      digits += c;
      any = true;
      if (dot) ++frac;
    } else if (c == '.' && !dot) {
      dot = true;
    } else {
      break;
    }
  }
  if (!any) return std::nullopt;
  long exponent = 0;
  if (i < text.size()) {
    if (text[i] != 'e' && text[i] != 'E') return std::nullopt;
    ++i;
    std::string e = text.substr(i);
    if (e.empty()) return std::nullopt;
    size_t j = (e[0] == '+' || e[0] == '-') ? 1 : 0;
    if (j == e.size() || e.find_first_not_of("0123456789", j) != std::string::npos || e.size() > 6)
      return std::nullopt;
    exponent = std::strtol(e.c_str(), nullptr, 10);
  }
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
  GiNaC::numeric value = digits.empty() ? GiNaC::numeric(0) : GiNaC::numeric(digits.c_str());
  long scale = exponent - frac;
  GiNaC::numeric ten(10);
  if (scale >= 0) value *= GiNaC::pow(ten, GiNaC::numeric(scale));
  else value /= GiNaC::pow(ten, GiNaC::numeric(-scale));
  return ex(value);
}

bool is_basis_name(const std::string& n) {
  if (!expand_algebra::is_cga()) return expand_algebra::is_basis_name(n);  // the algebra's own names
  static const std::set<std::string> names = {"e1", "e2", "e3", "einf", "e0", "ep", "em"};
  return names.count(n) > 0;
}

Multivector basis(const std::string& n) {
  if (!expand_algebra::is_cga()) return expand_algebra::basis(n);
  if (n == "e1") return Multivector::e1();
  if (n == "e2") return Multivector::e2();
  if (n == "e3") return Multivector::e3();
  if (n == "einf") return Multivector::einf();
  if (n == "e0") return Multivector::e0();
  const Multivector half_inf = Multivector::blade(4, GiNaC::numeric(1, 2));
  if (n == "ep") return half_inf - Multivector::e0();
  return half_inf + Multivector::e0();  // em
}

// The product kind of a chain expression: a geometric or outer product, or the reverse of one.
std::optional<algebra::ProductKind> Expander::chain_kind(const Expr& e) {
  if (e.kind == Expr::Kind::Binary && e.binary_op == front::BinaryOp::Geo) return algebra::ProductKind::Geometric;
  if (e.kind == Expr::Kind::Binary && e.binary_op == front::BinaryOp::Outer) return algebra::ProductKind::Outer;
  if (e.kind == Expr::Kind::Unary && e.unary_op == front::UnaryOp::Reverse) return chain_kind(*e.args.at(0));
  return std::nullopt;
}

// The factors of a chain of products of `kind`, in order, each evaluated once, left to right as written. Number
// factors and divisions by a number (`x*x/6` parses as x*(x/6)) go into `coeff` instead, so that the word is
// over the multivectors alone: x*x*x/6 is (1/6) x x x, a power of x.
void Expander::flatten(const Expr& e, algebra::ProductKind kind, expand_words::Word& out, ex& coeff) {
  const bool outer = kind == algebra::ProductKind::Outer;
  if (e.kind == Expr::Kind::Binary && e.binary_op == (outer ? front::BinaryOp::Outer : front::BinaryOp::Geo)) {
    if (auto w = outer ? hints::outer_with_number(e) : std::nullopt) hints::warn_once(kernel_.warnings, e.loc, *w);
    flatten(*e.args.at(0), kind, out, coeff);
    flatten(*e.args.at(1), kind, out, coeff);
    return;
  }
  if (e.kind == Expr::Kind::Binary && e.binary_op == front::BinaryOp::Div && e.args.at(1)->kind == Expr::Kind::Number)
    if (auto d = parse_number(e.args.at(1)->text); d && !d->is_zero()) {
      flatten(*e.args.at(0), kind, out, coeff);
      coeff /= *d;
      return;
    }
  if (e.kind == Expr::Kind::Number)
    if (auto d = parse_number(e.text)) {
      coeff *= *d;
      return;
    }
  if (e.kind == Expr::Kind::Unary && e.unary_op == front::UnaryOp::Reverse && chain_kind(*e.args.at(0)) == kind) {
    expand_words::Word inner;
    flatten(*e.args.at(0), kind, inner, coeff);
    const expand_words::Word r = expand_words::reversed(inner);
    out.insert(out.end(), r.begin(), r.end());
    return;
  }
  const Multivector v = eval(e);
  const expand_words::Word w = words_.expand(words_.atom(v, e.kind == Expr::Kind::Name ? e.text : ""), kind);
  out.insert(out.end(), w.begin(), w.end());
}

Multivector Expander::eval_chain(const Expr& e, algebra::ProductKind kind) {
  const bool whole_statement = &e == statement_value_;
  expand_words::Word w;
  ex coeff = 1;
  flatten(e, kind, w, coeff);
  if (w.empty()) return Multivector(coeff);  // numbers only: 2*3
  if (whole_statement && coeff.is_equal(1)) statement_word_ = {kind, w};
  const Multivector v = words_.evaluate(kind, w, e.loc, *this, whole_statement && coeff.is_equal(1));
  return coeff.is_equal(1) ? v : v * coeff;
}

Multivector Expander::lookup(const Expr& e) {
  const std::string& n = e.text;
  if (is_basis_name(n)) return basis(n);
  if (!frames_.empty()) {
    auto it = frames_.back().locals.find(n);
    if (it != frames_.back().locals.end()) return it->second;
  }
  auto it = globals_.find(n);
  if (it != globals_.end()) return it->second;
  if (macros_.count(n)) throw CompileError(e.loc, "'" + n + "' is a macro; call it as " + n + "(...)");
  // A free name: a new scalar input, in order of first use.
  warn_if_typo(n, e.loc);
  KernelInput in;
  in.name = n;
  in.blades = {0};
  GiNaC::realsymbol sym(unique_symbol_name(n));  // real: abs(a)^2 is a^2, not a*conjugate(a)
  zeros_.add_input(sym);
  in.symbols = {sym};
  kernel_.inputs.push_back(in);
  Multivector v(sym);
  globals_[n] = v;
  return v;
}

// A free name becomes an input; when it is one edit from a name the script or the language knows, that
// is more likely a typo (eiof for einf) than a new input, and silently wrong code: warn.
// Variables first (short ones too: Tt for T), then functions (expand/hints.hpp).
void Expander::warn_if_typo(const std::string& n, SourceLoc loc) {
  std::vector<std::string> known = {"e1", "e2", "e3", "einf", "e0", "ep", "em"};
  known.insert(known.end(), script_names_.begin(), script_names_.end());
  const std::vector<std::string> functions = expand_builtins::names();
  std::vector<std::string> inputs;  // a family of inputs (theta1 ... theta10) is no typo of another name
  for (const auto& in : kernel_.inputs) inputs.push_back(in.name);
  if (auto k = hints::for_read(n, known, functions, inputs))
    kernel_.warnings.push_back({loc, "'" + n + "' is used before it is assigned and becomes an input; did you mean '" +
                                         *k + "'?"});
}

Multivector Expander::eval(const Expr& e) {
  switch (e.kind) {
    case Expr::Kind::Number: {
      auto v = parse_number(e.text);
      if (!v) throw CompileError(e.loc, "malformed number '" + e.text + "'");
      return Multivector(*v);
    }
    case Expr::Kind::Name: return lookup(e);
    case Expr::Kind::MacroArg: {
      if (frames_.empty())
        throw CompileError(e.loc, "_P(" + std::to_string(e.index) + ") used outside a macro");
      const Frame& f = frames_.back();
      if (e.index < 1 || e.index > static_cast<int>(f.args.size()))
        throw CompileError(e.loc, "_P(" + std::to_string(e.index) + ") out of range: macro '" + f.macro +
                                      "' was called with " + std::to_string(f.args.size()) + " argument" +
                                      (f.args.size() == 1 ? "" : "s"));
      return f.args[e.index - 1];
    }
    case Expr::Kind::Unary: {
      if (e.unary_op == front::UnaryOp::Reverse)
        if (auto kind = chain_kind(*e.args.at(0))) return eval_chain(e, *kind);
      Multivector a = eval(*e.args.at(0));
      switch (e.unary_op) {
        case front::UnaryOp::Negate: return -a;
        case front::UnaryOp::Reverse: return a.reverse();
        case front::UnaryOp::Dual: return a.dual();
      }
      break;
    }
    case Expr::Kind::Binary: {
      if (auto kind = chain_kind(e)) return eval_chain(e, *kind);
      Multivector a = eval(*e.args.at(0));
      Multivector b = eval(*e.args.at(1));
      switch (e.binary_op) {
        case front::BinaryOp::Add: return a + b;
        case front::BinaryOp::Sub: return a - b;
        case front::BinaryOp::Geo:
        case front::BinaryOp::Outer: break;  // chains (eval_chain)
        case front::BinaryOp::Inner: return product(algebra::ProductKind::Inner, a, b, e.loc);
        case front::BinaryOp::Div: return divide(a, b, *e.args.at(1));
      }
      break;
    }
    case Expr::Kind::Call: return call(e);
    case Expr::Kind::Compare:
    case Expr::Kind::Logic:
      throw CompileError(e.loc, "'" + e.text + "' may only appear in the condition of an 'if'");
  }
  throw CompileError(e.loc, "internal error: unknown expression kind");
}

Multivector Expander::divide(const Multivector& a, const Multivector& b_in, const Expr& be) {
  Multivector b = scalar_part_if_scalar(b_in);
  if (b.is_zero()) throw CompileError(be.loc, "division by zero");
  if (b.is_scalar()) return guarded(be.loc, [&] { return a / b.scalar(); });
  return guarded(be.loc, [&] {
    try {
      auto zero = [&](const ex& c) { return vanishes(c); };
      const auto inv = declared_versor(b) ? expand_inverse::versor_inverse(b, zero) : expand_inverse::inverse(b, zero);
      return (a * inv.numerator) / inv.denominator;
    } catch (const expand_inverse::NotInvertible& e) {
      throw CompileError(be.loc, e.message);
    }
  });
}

// Is b the value of a name the script declares a versor (`#pragma versor`, or a `normalized` input)?
bool Expander::declared_versor(const Multivector& b) const {
  auto is_value_of = [&](const std::string& name) {
    auto it = globals_.find(name);
    return it != globals_.end() && it->second.terms().size() == b.terms().size() && it->second == b;
  };
  for (const auto& n : pragmas_.versors())
    if (is_value_of(n.name)) return true;
  for (const auto& n : kernel_.normalized)
    if (is_value_of(n.name)) return true;
  return false;
}

}  // namespace cgagen::expand_detail
