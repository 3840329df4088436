// Canonical keys, product/sum decomposition and op counting of GiNaC expressions (see lower.hpp).
#include "lower/lower.hpp"

#include <algorithm>
#include <sstream>

namespace cgagen::opt {

using namespace GiNaC;

namespace {

std::string numeric_text(const ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

}  // namespace

const std::string& CanonicalKeys::key(const ex& e) { return entry(e).full; }
int CanonicalKeys::sign(const ex& e) { return entry(e).sign; }
const std::string& CanonicalKeys::magnitude(const ex& e) { return entry(e).magnitude; }
bool CanonicalKeys::less(const ex& a, const ex& b) {
  const Entry& x = entry(a);
  const Entry& y = entry(b);
  return x.magnitude != y.magnitude ? x.magnitude < y.magnitude : x.full < y.full;
}

const CanonicalKeys::Entry& CanonicalKeys::entry(const ex& e) {
  auto it = memo_.find(e);
  if (it != memo_.end()) return it->second;
  Entry r{1, "", ""};
  if (symbolic::is_symbol(e)) {
    auto n = names_.find(e);
    r.magnitude = n != names_.end() ? n->second : ex_to<symbol>(e).get_name();
  } else if (symbolic::is_numeric(e)) {
    const numeric& v = ex_to<numeric>(e);
    if (v.is_real() && v.is_negative()) r.sign = -1;
    r.magnitude = numeric_text(r.sign < 0 ? ex(-v) : e);
  } else if (is_a<constant>(e)) {
    r.magnitude = numeric_text(e);
  } else if (symbolic::is_add(e)) {
    std::vector<std::pair<std::string, int>> terms;
    for (size_t i = 0; i < e.nops(); ++i) {
      const Entry& t = entry(e.op(i));
      terms.push_back({t.magnitude, t.sign});
    }
    std::sort(terms.begin(), terms.end());
    r.sign = terms.front().second;
    r.magnitude = "(+";
    for (auto& [m, sg] : terms) r.magnitude += std::string(sg * r.sign > 0 ? " " : " -") + m;
    r.magnitude += ")";
  } else if (symbolic::is_mul(e)) {
    std::vector<std::string> parts;
    for (size_t i = 0; i < e.nops(); ++i) {
      const Entry& f = entry(e.op(i));
      r.sign *= f.sign;
      if (!(symbolic::is_numeric(e.op(i)) && f.magnitude == "1")) parts.push_back(f.magnitude);
    }
    std::sort(parts.begin(), parts.end());
    if (parts.size() == 1) {  // -x has the magnitude of x
      r.magnitude = parts[0];
    } else {
      r.magnitude = "(*";
      for (auto& p : parts) r.magnitude += " " + p;
      r.magnitude += ")";
    }
  } else if (symbolic::is_power(e)) {
    const Entry& b = entry(e.op(0));
    const ex& x = e.op(1);
    if (symbolic::is_numeric(x) && ex_to<numeric>(x).is_integer()) {
      if (ex_to<numeric>(x).is_odd()) r.sign = b.sign;
      r.magnitude = "(^ " + b.magnitude + " " + numeric_text(x) + ")";
    } else {
      r.magnitude = "(^ " + b.full + " " + entry(x).full + ")";
    }
  } else if (is_a<function>(e)) {
    r.magnitude = "(" + ex_to<function>(e).get_name();
    for (size_t i = 0; i < e.nops(); ++i) r.magnitude += " " + entry(e.op(i)).full;
    r.magnitude += ")";
  } else {
    r.magnitude = numeric_text(e);
  }
  r.full = (r.sign < 0 ? "-" : "") + r.magnitude;
  return memo_.emplace(e, std::move(r)).first->second;
}

namespace {

// Returns e itself where nothing in it changes: most of a program is oriented already when a pass runs
// again, and rebuilding a sum or product from its own operands makes GiNaC sort them again (an equal
// expression, at the price of a fresh allocation and canonicalization per node).
class Orienter {
 public:
  explicit Orienter(CanonicalKeys& keys) : keys_(keys) {}
  ex operator()(const ex& e) {
    if (symbolic::is_symbol_number_or_constant(e)) return e;
    auto it = memo_.find(e);
    if (it != memo_.end()) return it->second.unchanged ? e : it->second.value;
    ex r;
    bool unchanged = true;
    auto child = [&](const ex& x) {
      ex y = (*this)(x);
      if (!are_ex_trivially_equal(x, y)) unchanged = false;
      return y;
    };
    if (symbolic::is_add(e)) {
      exvector terms;
      for (size_t i = 0; i < e.nops(); ++i) terms.push_back(child(e.op(i)));
      if (!unchanged) r = dynallocate<add>(terms);
    } else if (symbolic::is_mul(e)) {
      exvector factors;
      bool negate = false;
      for (size_t i = 0; i < e.nops(); ++i) {
        ex f = child(e.op(i));
        if (symbolic::is_add(f) && keys_.sign(f) < 0) {
          f = -f;
          negate = !negate;
          unchanged = false;
        }
        factors.push_back(f);
      }
      if (!unchanged) {
        r = dynallocate<mul>(factors);
        if (negate) r = -r;
      }
    } else if (symbolic::is_power(e)) {
      ex base = child(e.op(0));
      const ex& x = e.op(1);
      bool negate = false;
      if (symbolic::is_numeric(x) && ex_to<numeric>(x).is_integer() && symbolic::is_add(base) && keys_.sign(base) < 0) {
        base = -base;
        negate = ex_to<numeric>(x).is_odd();
        unchanged = false;
      }
      ex exponent = child(x);
      if (!unchanged) {
        r = pow(base, exponent);
        if (negate) r = -r;
      }
    } else {
      struct F : map_function {
        Orienter* self;
        ex operator()(const ex& x) override { return (*self)(x); }
      } f;
      f.self = this;
      r = e.map(f);  // e itself when no operand changes
      unchanged = are_ex_trivially_equal(r, e);
    }
    if (unchanged) r = e;
    memo_.emplace(e, Result{r, unchanged});
    return r;
  }

 private:
  struct Result {
    ex value;
    bool unchanged;  // value is e: a later equal e is returned as it is
  };
  CanonicalKeys& keys_;
  symbolic::ExHashMap<Result> memo_;
};

}  // namespace

ex orient_sums(const ex& e, CanonicalKeys& keys) { return Orienter(keys)(e); }

bool is_sqrt(const ex& e) {
  return symbolic::is_power(e) && symbolic::is_numeric(e.op(1)) && ex_to<numeric>(e.op(1)) == numeric(1, 2);
}

static void add_factor(ProductParts& p, const ex& f, CanonicalKeys& keys) {
  if (symbolic::is_numeric(f)) {
    p.coeff *= ex_to<numeric>(f);
    return;
  }
  if (symbolic::is_power(f) && symbolic::is_numeric(f.op(1))) {
    numeric n = ex_to<numeric>(f.op(1));
    if (n.is_integer()) {
      int k = n.to_int();
      ex base = f.op(0);
      if (symbolic::is_add(base) && keys.sign(base) < 0) {  // orient the sum; odd powers carry the sign out
        base = -base;
        if (k % 2 != 0) p.coeff = -p.coeff;
      }
      if (k > 0) p.num.push_back({base, k});
      else p.den.push_back({base, -k});
      return;
    }
    if (n.is_negative()) {  // x^(-1/2) -> 1/sqrt(x)
      p.den.push_back({pow(f.op(0), -n), 1});
      return;
    }
  }
  if (symbolic::is_add(f) && keys.sign(f) < 0) {
    p.coeff = -p.coeff;
    p.num.push_back({-f, 1});
    return;
  }
  p.num.push_back({f, 1});
}

ProductParts split_product(const ex& e, CanonicalKeys& keys) {
  ProductParts p;
  if (symbolic::is_mul(e)) {
    for (size_t i = 0; i < e.nops(); ++i) add_factor(p, e.op(i), keys);
  } else {
    add_factor(p, e, keys);
  }
  auto by_key = [&](const Factor& a, const Factor& b) {
    if (keys.less(a.base, b.base)) return true;
    if (keys.less(b.base, a.base)) return false;
    return a.exponent < b.exponent;
  };
  std::sort(p.num.begin(), p.num.end(), by_key);
  std::sort(p.den.begin(), p.den.end(), by_key);
  return p;
}

bool is_negative_term(const ex& e, CanonicalKeys& keys) { return !symbolic::is_add(e) && keys.sign(e) < 0; }

std::vector<ex> sum_terms(const ex& sum, CanonicalKeys& keys) {
  std::vector<ex> terms;
  for (size_t i = 0; i < sum.nops(); ++i) terms.push_back(sum.op(i));
  std::stable_sort(terms.begin(), terms.end(), [&](const ex& a, const ex& b) {
    bool na = is_negative_term(a, keys), nb = is_negative_term(b, keys);
    if (na != nb) return !na;
    return keys.less(a, b);
  });
  return terms;
}

std::vector<ex> ordered_children(const ex& e, CanonicalKeys& keys) {
  std::vector<ex> c;
  for (size_t i = 0; i < e.nops(); ++i) c.push_back(e.op(i));
  if (symbolic::is_add(e) || symbolic::is_mul(e))
    std::stable_sort(c.begin(), c.end(), [&](const ex& a, const ex& b) { return keys.less(a, b); });
  return c;
}

static OpCounts count_atom(const ex& b, CanonicalKeys& keys);

OpCounts count_ops(const ex& e, CanonicalKeys& keys) {
  OpCounts c;
  if (symbolic::is_symbol_number_or_constant(e)) return c;
  if (symbolic::is_add(e)) {
    c.add += static_cast<long>(e.nops()) - 1;
    for (size_t i = 0; i < e.nops(); ++i) c += count_ops(e.op(i), keys);
    return c;
  }
  ProductParts p = split_product(e, keys);
  long nnum = 0, nden = 0;
  for (auto& f : p.num) {
    nnum += f.exponent;
    OpCounts a = count_atom(f.base, keys);
    for (int k = 0; k < f.exponent; ++k) c += a;
  }
  for (auto& f : p.den) {
    nden += f.exponent;
    OpCounts a = count_atom(f.base, keys);
    for (int k = 0; k < f.exponent; ++k) c += a;
  }
  if (nnum > 1) c.mul += nnum - 1;
  if (nnum > 0 && abs(p.coeff) != 1) c.mul += 1;
  if (nden > 1) c.mul += nden - 1;
  if (nden > 0) c.div += 1;
  return c;
}

static OpCounts count_atom(const ex& b, CanonicalKeys& keys) {
  OpCounts c;
  if (symbolic::is_symbol_number_or_constant(b)) return c;
  if (symbolic::is_add(b) || symbolic::is_mul(b)) return count_ops(b, keys);
  if (symbolic::is_power(b)) {  // a non-integer power: sqrt or pow
    c.call += 1;
    c += count_ops(b.op(0), keys);
    if (!is_sqrt(b)) c += count_ops(b.op(1), keys);
    return c;
  }
  if (is_a<function>(b)) {
    c.call += 1;
    for (size_t i = 0; i < b.nops(); ++i) c += count_ops(b.op(i), keys);
    return c;
  }
  return c;
}

}  // namespace cgagen::opt
