// The expression printer (printer.hpp): one expression as text in a target's syntax.
#include "emit/printer.hpp"

#include "symbolic/select.hpp"

namespace cgagen::emit {

using namespace GiNaC;

std::string Printer::print(const ex& e, int prec) {
  if (is_a<numeric>(e)) {
    std::string s = number(ex_to<numeric>(e));
    return (prec >= 1 && ex_to<numeric>(e).is_negative() && sx_.constant.empty()) ? "(" + s + ")" : s;
  }
  if (is_a<symbol>(e)) {
    auto it = code_.find(e);
    if (it == code_.end()) throw std::logic_error("cgagen emitter: unknown symbol " + ex_to<symbol>(e).get_name());
    return it->second;
  }
  if (is_a<constant>(e)) return number(numeric(ex_to<numeric>(e.evalf()).to_double()));
  if (prec == 0 && !sx_.select_bare.empty() && cgagen::symbolic::is_select(e)) return select(e, sx_.select_bare);
  if (is_a<add>(e)) {
    std::string s;
    bool first = true;
    for (const ex& t : opt::sum_terms(e, keys_)) {
      bool neg = opt::is_negative_term(t, keys_);
      ex a = neg ? ex(-t) : t;
      if (first) s += neg ? negated(print(a, 1)) : print(a, 0);
      else s += (neg ? " - " : " + ") + print(a, 1);
      first = false;
    }
    return prec >= 1 ? "(" + s + ")" : s;
  }
  return print_product(e, prec);
}

std::string Printer::print_product(const ex& e, int prec) {
  opt::ProductParts p = opt::split_product(e, keys_);
  std::vector<std::string> num;
  numeric c = abs(p.coeff);
  if (c != 1 || p.num.empty()) num.push_back(number(c));
  for (const auto& f : p.num) {
    std::string a = atom(f.base);
    for (int k = 0; k < f.exponent; ++k) num.push_back(a);
  }
  std::vector<std::string> den;
  for (const auto& f : p.den) {
    std::string a = atom(f.base);
    for (int k = 0; k < f.exponent; ++k) den.push_back(a);
  }
  std::string s;
  for (size_t i = 0; i < num.size(); ++i) s += (i ? sx_.mul : "") + num[i];
  if (!den.empty()) {
    std::string d;
    for (size_t i = 0; i < den.size(); ++i) d += (i ? sx_.mul : "") + den[i];
    s += sx_.div + (den.size() > 1 ? "(" + d + ")" : d);
  }
  bool compound = num.size() + den.size() > 1;
  if (p.coeff.is_negative()) {
    s = negated(den.empty() ? s : "(" + s + ")");
    return prec >= 1 ? "(" + s + ")" : s;
  }
  return (compound && prec >= 2) || (!den.empty() && prec >= 1) ? "(" + s + ")" : s;
}

std::string Printer::atom(const ex& b) {
  if (is_a<symbol>(b) || is_a<numeric>(b) || is_a<constant>(b)) return print(b, 2);
  if (is_a<add>(b) || is_a<mul>(b)) return print(b, 2);
  if (opt::is_sqrt(b)) return call("sqrt", print(b.op(0)));
  if (is_a<power>(b)) return call("pow", print(b.op(0)) + ", " + print(b.op(1)));
  if (cgagen::symbolic::is_select(b)) return select(b, sx_.select);
  if (is_a<function>(b)) {
    std::string name = ex_to<function>(b).get_name();
    std::string s;
    for (size_t i = 0; i < b.nops(); ++i) s += (i ? ", " : "") + print(b.op(i));
    return call(name, s);
  }
  throw std::logic_error("cgagen emitter: cannot print expression of this kind");
}

std::string Printer::select(const ex& b, const std::string& pattern) {
  const std::string op = cgagen::symbolic::select_operator(b);
  auto it = sx_.compare_names.find(op);
  return fill_pattern(pattern, {{"a", print(b.op(0), 1)},
                                {"b", print(b.op(1), 1)},
                                {"op", it == sx_.compare_names.end() ? op : it->second},
                                {"x", print(b.op(2))},
                                {"y", print(b.op(3))},
                                {"T", prec_.type}});
}

std::string Printer::number(const numeric& v) const {
  const std::string s = literal(v, target_, single_);
  return sx_.constant.empty() ? s : fill_pattern(sx_.constant, {{"value", s}});
}

std::string Printer::negated(const std::string& operand) const { return fill_pattern(sx_.negate, {{"x", operand}}); }

std::string Printer::call(const std::string& name, const std::string& args) const {
  auto it = sx_.math_names.find(name);
  std::string fn = it == sx_.math_names.end() ? name : it->second;
  if (fn.find("${") != std::string::npos) return fill_pattern(fn, {{"args", args}, {"T", prec_.type}});
  fn = fill_pattern(sx_.math_prefix, {{"T", prec_.type}}) + fn;
  return fill_pattern(sx_.call, {{"fn", fn}, {"args", args}});
}

}  // namespace cgagen::emit
