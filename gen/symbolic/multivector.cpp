// Symbolic multivector operations (see multivector.hpp).
#include "symbolic/multivector.hpp"

#include "symbolic/budget.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/node_cache.hpp"
#include "symbolic/select.hpp"

#include "algebra/algebra.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <sstream>
#include <vector>

namespace cgagen::symbolic {
namespace {

// Does e contain a power with a negative exponent (a denominator)? Only then is normal() worth calling.
bool has_denominator(const GiNaC::ex& e) { return has_negative_power(e); }

// Terms of an expanded coefficient (a sum's terms; anything else is one).
std::size_t term_count(const GiNaC::ex& e) { return symbolic::is_add(e) ? e.nops() : 1; }

GiNaC::ex to_ex(const algebra::Rational& r) { return GiNaC::numeric(r.num) / GiNaC::numeric(r.den); }

// Canonical form of a coefficient: expanded, and 0 when it normalizes to 0.
GiNaC::ex canonical(const GiNaC::ex& c) {
  GiNaC::ex e = c.expand();
  if (!e.is_zero() && has_denominator(e) && is_zero_rational(e)) return 0;
  return e;
}

}  // namespace

namespace {

// A symbol's value at probe point k: irregular in [0.3, 1.7), from its name alone (the same in every
// process, and the same for every expression, so values of shared nodes can be kept). Evenly spaced values
// would put e.g. three points on one line (a pole of circle3).
GiNaC::numeric probe_value(const std::string& name, int k) {
  std::uint64_t h = 0xcbf29ce484222325ull ^ static_cast<std::uint64_t>(k + 1);
  for (unsigned char c : name) h = (h ^ c) * 0x100000001b3ull;
  h = h * 6364136223846793005ull + 1442695040888963407ull;
  return GiNaC::numeric(static_cast<long>(300 + (h >> 33) % 1400), 1000);
}

std::set<GiNaC::ex, GiNaC::ex_is_less> symbols_of(const GiNaC::ex& x) {
  std::set<GiNaC::ex, GiNaC::ex_is_less> symbols;
  collect_symbols_into(x, symbols);
  return symbols;
}

// Two fixed irregular points for the symbols of x.
std::vector<GiNaC::exmap> probe_points(const GiNaC::ex& x) {
  std::vector<GiNaC::exmap> points(2);
  for (const GiNaC::ex& sym : symbols_of(x))
    for (int k = 0; k < 2; ++k) points[static_cast<size_t>(k)][sym] = probe_value(GiNaC::ex_to<GiNaC::symbol>(sym).get_name(), k);
  return points;
}

// x in floats at probe point k, each shared node once; the values of large nodes are kept in the open
// NodeCacheScope (a root of a large sum under every coefficient of a normalized value). Throws at a pole.
GiNaC::numeric float_value(const GiNaC::ex& x, int k) {
  using namespace GiNaC;
  NodeCaches* caches = NodeCaches::current();
  auto* cache = caches ? &caches->probe_values[static_cast<size_t>(k)] : nullptr;
  std::unordered_map<const basic*, numeric> memo;
  auto eval = [&](auto&& self, const ex& e) -> numeric {
    if (symbolic::is_numeric(e)) return ex_to<numeric>(ex_to<numeric>(e).evalf());
    if (auto it = memo.find(node_of(e)); it != memo.end()) return it->second;  // symbols too
    if (symbolic::is_symbol(e)) {
      const numeric v = ex_to<numeric>(probe_value(ex_to<symbol>(e).get_name(), k).evalf());
      memo.emplace(node_of(e), v);
      return v;
    }
    if (cache)
      if (const numeric* kept = cache->find(e)) return *kept;
    numeric v;
    if (symbolic::is_add(e) || symbolic::is_mul(e)) {
      const bool product = symbolic::is_mul(e);
      const auto& pairs = pairs_of(e);
      v = product ? numeric(1) : numeric(0);
      for (const auto& p : pairs) {
        const numeric r = self(self, p.rest), c = ex_to<numeric>(p.coeff);
        v = product ? v * (c.is_equal(numeric(1)) ? r : ex_to<numeric>(evalf(pow(r, c)))) : v + c * r;
      }
      if (e.nops() > pairs.size()) {  // the numeric overall coefficient
        const numeric oc = ex_to<numeric>(ex_to<numeric>(e.op(e.nops() - 1)).evalf());
        v = product ? v * oc : v + oc;
      }
    } else if (symbolic::is_power(e)) {
      const ex f = evalf(pow(self(self, e.op(0)), self(self, e.op(1))));
      if (!symbolic::is_numeric(f)) throw std::runtime_error("not a number at the probe");
      v = ex_to<numeric>(f);
    } else if (is_a<function>(e)) {
      // A function call: GiNaC's function at its arguments' values (an argument is often a large sum, the
      // root of a normalized value: substituting into it would rebuild it node by node).
      exvector args;
      for (size_t i = 0; i < e.nops(); ++i) args.push_back(self(self, e.op(i)));
      const ex f = evalf(function(ex_to<function>(e).get_serial(), args));
      if (!symbolic::is_numeric(f)) throw std::runtime_error("not a number at the probe");
      v = ex_to<numeric>(f);
    } else {
      // Anything else: GiNaC on the node with its operands' values.
      exmap at;
      for (const ex& sym : symbols_of(e)) at[sym] = probe_value(ex_to<symbol>(sym).get_name(), k).evalf();
      const ex f = DagSubs(at)(e).evalf();
      if (!symbolic::is_numeric(f)) throw std::runtime_error("not a number at the probe");
      v = ex_to<numeric>(f);
    }
    memo.emplace(node_of(e), v);
    if (cache && (!symbolic::is_mul(e) || e.nops() > 8)) cache->keep(e, v);
    return v;
  };
  return eval(eval, x);
}

// True when x evaluates in floats far from 0 at a probe point: then it is not identically zero (values of a
// few units cannot cancel to that). Cheap on an unexpanded x, which is where it pays.
bool clearly_nonzero(const GiNaC::ex& x) {
  using namespace GiNaC;
  for (int k = 0; k < 2; ++k) {
    try {
      if (abs(float_value(x, k)) > numeric(1, 1000)) return true;
    } catch (const std::exception&) {
      // a pole at the probe
    }
  }
  return false;
}

}  // namespace

namespace {

// After clearly_nonzero found nothing: exact arithmetic at the same points (a nonzero value is a proof),
// then normal().
bool zero_after_float_probes(const GiNaC::ex& x, const std::vector<GiNaC::exmap>& points) {
  using namespace GiNaC;
  for (const exmap& at : points) {
    try {
      const ex v = DagSubs(at)(x);
      if (symbolic::is_numeric(v) && ex_to<numeric>(v).is_rational() && !v.is_zero()) return false;
    } catch (const std::exception&) {
      // a pole at the probe: decide exactly
    }
  }
  return normal(x).is_zero();
}

}  // namespace

bool is_zero_rational(const GiNaC::ex& x) {
  return !clearly_nonzero(x) && zero_after_float_probes(x, probe_points(x));
}

bool is_identically_zero(const GiNaC::ex& e) {
  // The float probes run on the unexpanded form: that spares expanding large inlined values that are
  // plainly not zero. Expanding cannot bring in symbols, so the same points serve the exact checks.
  if (clearly_nonzero(e)) return false;
  const std::vector<GiNaC::exmap> points = probe_points(e);
  const GiNaC::ex x = e.expand();
  if (x.is_zero()) return true;
  return has_denominator(x) && zero_after_float_probes(x, points);
}

Multivector::Multivector(const GiNaC::ex& scalar) { set(0, scalar); }

Multivector Multivector::blade(BladeIndex i, const GiNaC::ex& coeff) {
  Multivector m;
  m.set(i, coeff);
  return m;
}

GiNaC::ex Multivector::coeff(BladeIndex i) const {
  auto it = terms_.find(i);
  return it == terms_.end() ? GiNaC::ex(0) : it->second;
}

void Multivector::set(BladeIndex i, const GiNaC::ex& c) {
  if (i < 0 || i >= algebra::blade_count()) throw std::out_of_range("blade index out of range");
  GiNaC::ex e = canonical(c);
  if (e.is_zero()) terms_.erase(i);
  else terms_[i] = e;
}

bool Multivector::is_homogeneous(int k) const {
  for (const auto& [b, c] : terms_)
    if (algebra::blade_grade(b) != k) return false;
  return true;
}

Multivector Multivector::operator-() const {
  Multivector r = *this;
  for (auto& [b, c] : r.terms_) c = -c;  // negating an expanded sum keeps it expanded and nonzero
  return r;
}

Multivector& Multivector::operator+=(const Multivector& b) {
  for (const auto& [i, c] : b.terms_) set(i, coeff(i) + c);
  return *this;
}

Multivector& Multivector::operator-=(const Multivector& b) {
  for (const auto& [i, c] : b.terms_) set(i, coeff(i) - c);
  return *this;
}

Multivector Multivector::product(algebra::ProductKind kind, const Multivector& a, const Multivector& b) {
  // Sparse in the result blades: an algebra may have 65,536 of them (ccga); a product touches few.
  std::map<BladeIndex, GiNaC::exvector> acc;
  std::map<BladeIndex, std::size_t> estimate;  // terms of each coefficient once expanded
  for (const auto& [i, ca] : a.terms_) {
    for (const auto& [j, cb] : b.terms_) {
      const auto& terms = algebra::product(kind, i, j);
      if (terms.empty()) continue;
      GiNaC::ex ab = ca * cb;
      const std::size_t n = term_count(ca) * term_count(cb);
      for (const auto& t : terms) {
        acc[t.blade].push_back(t.coeff == algebra::Rational(1) ? ab : to_ex(t.coeff) * ab);
        estimate[t.blade] += n;
      }
    }
  }
  for (const auto& [k, n] : estimate)
    if (n) WorkBudget::charge(n);
  Multivector r;
  for (auto& [k, terms] : acc)
    if (!terms.empty()) r.set(k, GiNaC::add(terms));
  return r;
}

Multivector operator*(const Multivector& a, const Multivector& b) {
  return Multivector::product(algebra::ProductKind::Geometric, a, b);
}
Multivector operator^(const Multivector& a, const Multivector& b) {
  return Multivector::product(algebra::ProductKind::Outer, a, b);
}
Multivector inner(const Multivector& a, const Multivector& b) {
  return Multivector::product(algebra::ProductKind::Inner, a, b);
}

Multivector graded_product(Multivector::Graded kind, const Multivector& a, const Multivector& b) {
  using G = Multivector::Graded;
  std::map<BladeIndex, GiNaC::exvector> acc;
  std::map<BladeIndex, std::size_t> estimate;
  for (const auto& [i, ca] : a.terms_) {
    const int r = algebra::blade_grade(i);
    for (const auto& [j, cb] : b.terms_) {
      const int s = algebra::blade_grade(j);
      int want = 0;
      switch (kind) {
        case G::LeftContraction: want = s - r; break;
        case G::RightContraction: want = r - s; break;
        case G::Scalar: want = 0; break;
        case G::Dot: want = r > s ? r - s : s - r; break;
      }
      if (want < 0) continue;
      const auto& terms = algebra::product(algebra::ProductKind::Geometric, i, j);
      GiNaC::ex ab;
      bool any = false;
      for (const auto& t : terms) {
        if (algebra::blade_grade(t.blade) != want) continue;
        if (!any) ab = ca * cb, any = true;
        estimate[t.blade] += term_count(ca) * term_count(cb);
        acc[t.blade].push_back(t.coeff == algebra::Rational(1) ? ab : to_ex(t.coeff) * ab);
      }
    }
  }
  for (const auto& [k, n] : estimate)
    if (n) WorkBudget::charge(n);
  Multivector out;
  for (auto& [k, terms] : acc)
    if (!terms.empty()) out.set(k, GiNaC::add(terms));
  return out;
}

Multivector operator*(const GiNaC::ex& s, const Multivector& a) {
  Multivector r;
  for (const auto& [b, c] : a.terms_) {
    WorkBudget::charge(term_count(s) * term_count(c));
    r.set(b, s * c);
  }
  return r;
}

Multivector operator/(const Multivector& a, const GiNaC::ex& s) {
  Multivector r;
  for (const auto& [b, c] : a.terms_) r.set(b, c / s);
  return r;
}

Multivector Multivector::reverse() const {
  Multivector r = *this;
  for (auto& [b, c] : r.terms_)
    if (algebra::reverse_sign(b) < 0) c = -c;
  return r;
}

Multivector Multivector::involute() const {
  Multivector r = *this;
  for (auto& [b, c] : r.terms_)
    if (algebra::involution_sign(b) < 0) c = -c;
  return r;
}

Multivector Multivector::grade(int k) const {
  Multivector r;
  for (const auto& [b, c] : terms_)
    if (algebra::blade_grade(b) == k) r.terms_[b] = c;
  return r;
}

Multivector Multivector::grade_above(int k) const {
  Multivector r;
  for (const auto& [b, c] : terms_)
    if (algebra::blade_grade(b) > k) r.terms_[b] = c;
  return r;
}

Multivector Multivector::dual() const {
  const algebra::Algebra& alg = algebra::current();
  if (alg.name() == "cga" && alg.spec().cga_idents) return *this * blade(31, -1);  // CGA, exactly as always
  const BladeIndex top = alg.blade_count() - 1;
  if (auto inv = alg.inverse_pseudoscalar()) return *this * blade(top, to_ex(*inv));
  // A degenerate metric (PGA) has no inverse pseudoscalar. The dual is then Gaalop's complement map (its
  // 3dpga/2dpga macros): the coefficient of blade B moves to the blade of the vectors B lacks, with sign +1
  // in this algebra's blade names (e0^e1 <-> e2^e3). It is an involution: dual(dual(A)) = A.
  Multivector r;
  for (const auto& [b, c] : terms_)
    r.terms_[alg.index(alg.bits(b) ^ alg.bits(top))] = c;
  return r;
}

Multivector Multivector::undual() const {
  const algebra::Algebra& alg = algebra::current();
  const bool cga = alg.name() == "cga" && alg.spec().cga_idents;
  if (!cga && !alg.inverse_pseudoscalar()) return dual();  // the complement map is an involution
  // dual(A) = A * d with d a multiple of the pseudoscalar, so d * d is a nonzero scalar and d^-1 = d / (d*d).
  const Multivector d = Multivector(GiNaC::ex(1)).dual();
  const Multivector dd = d * d;
  return *this * (d / dd.scalar());
}

Multivector Multivector::expanded() const {
  return map([](const GiNaC::ex& c) { return c; });
}

std::string Multivector::str() const {
  if (terms_.empty()) return "0";
  std::ostringstream os;
  bool first = true;
  for (const auto& [b, c] : terms_) {
    if (!first) os << " + ";
    first = false;
    if (b == 0) {
      os << c;
    } else if (c.is_equal(GiNaC::ex(1))) {
      os << algebra::blade_name(b);
    } else {
      os << "(" << c << ")*" << algebra::blade_name(b);
    }
  }
  return os.str();
}

bool operator==(const Multivector& a, const Multivector& b) { return (a - b).is_zero(); }

namespace {
bool is_negative_number(const GiNaC::ex& x) {
  return symbolic::is_numeric(x) && GiNaC::ex_to<GiNaC::numeric>(x).is_negative();
}

bool has_negative_power(const GiNaC::ex& e, std::unordered_set<const GiNaC::basic*>& seen) {
  using namespace GiNaC;
  if (e.nops() == 0 || !seen.insert(node_of(e)).second) return false;
  if (symbolic::is_add_or_mul(e)) {
    const bool product = symbolic::is_mul(e);  // a product's factor x^k is the pair (x, k)
    for (const auto& p : pairs_of(e))
      if ((product && is_negative_number(p.coeff)) || has_negative_power(p.rest, seen)) return true;
    return false;
  }
  if (symbolic::is_power(e) && is_negative_number(e.op(1))) return true;
  for (size_t i = 0; i < e.nops(); ++i)
    if (has_negative_power(e.op(i), seen)) return true;
  return false;
}
}  // namespace

bool has_negative_power(const GiNaC::ex& e) {
  std::unordered_set<const GiNaC::basic*> seen;
  return has_negative_power(e, seen);
}

bool has_nonreal_number(const GiNaC::ex& e) {
  using namespace GiNaC;
  std::unordered_set<const basic*> seen;
  auto nonreal = [](const ex& x) { return symbolic::is_numeric(x) && !ex_to<numeric>(x).is_real(); };
  auto walk = [&](auto&& self, const ex& x) -> bool {
    if (symbolic::is_numeric(x)) return nonreal(x);
    if (x.nops() == 0 || !seen.insert(node_of(x)).second) return false;
    if (symbolic::is_add_or_mul(x)) {
      const auto& pairs = pairs_of(x);
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (nonreal(pairs[i].coeff) || self(self, pairs[i].rest)) return true;
        // A product's number^exponent (2^(1/2)): what its operand evaluates to.
        if (symbolic::is_mul(x) && symbolic::is_numeric(pairs[i].rest) && visit_nodes_once(x.op(i), nonreal)) return true;
      }
      return x.nops() > pairs.size() && nonreal(x.op(x.nops() - 1));  // the overall coefficient
    }
    for (std::size_t i = 0; i < x.nops(); ++i)
      if (self(self, x.op(i))) return true;
    return false;
  };
  return walk(walk, e);
}

void collect_symbols_into(const GiNaC::ex& x, std::set<GiNaC::ex, GiNaC::ex_is_less>& symbols) {
  using namespace GiNaC;
  std::unordered_set<const basic*> seen;
  auto walk = [&](auto&& self, const ex& e) -> void {
    if (symbolic::is_symbol(e)) {
      symbols.insert(e);
      return;
    }
    if (e.nops() == 0 || !seen.insert(node_of(e)).second) return;
    if (symbolic::is_add_or_mul(e)) {
      for (const auto& p : pairs_of(e)) self(self, p.rest);
    } else {
      for (size_t i = 0; i < e.nops(); ++i) self(self, e.op(i));
    }
  };
  walk(walk, x);
}

std::size_t tree_symbol_count(const GiNaC::ex& e) {
  // Large shared nodes (a root's argument under every coefficient of a normalized value) are counted once
  // per open NodeCacheScope.
  constexpr std::size_t kCachedFrom = 256;
  NodeCaches* caches = NodeCaches::current();
  auto* cache = caches ? &caches->symbol_counts : nullptr;
  std::unordered_map<const GiNaC::basic*, std::size_t> memo;  // nodes of e, alive while e is
  auto count = [&](auto&& self, const GiNaC::ex& x) -> std::size_t {
    if (symbolic::is_symbol(x)) return 1;
    if (x.nops() == 0) return 0;
    auto it = memo.find(node_of(x));
    if (it != memo.end()) return it->second;
    if (cache)
      if (const std::size_t* kept = cache->find(x)) return *kept;
    std::size_t n = 0;
    if (symbolic::is_add_or_mul(x)) {
      // Sums and products: the coefficients, exponents and overall coefficient are numbers (no symbols).
      for (const auto& pair : pairs_of(x)) n += self(self, pair.rest);
    } else {
      for (std::size_t i = 0; i < x.nops(); ++i) n += self(self, x.op(i));
    }
    memo.emplace(node_of(x), n);
    if (cache && n >= kCachedFrom) cache->keep(x, n);
    return n;
  };
  return count(count, e);
}

std::optional<GiNaC::numeric> evalf_at(const GiNaC::ex& e, const GiNaC::exmap& at, KeptValues* kept) {
  using namespace GiNaC;
  std::unordered_map<const basic*, std::optional<numeric>> memo;  // nodes of e, alive while e is
  auto as_number = [](const ex& f) -> std::optional<numeric> {
    if (!symbolic::is_numeric(f)) return std::nullopt;
    return ex_to<numeric>(f);
  };
  auto eval = [&](auto&& self, const ex& x) -> std::optional<numeric> {
    if (symbolic::is_numeric(x)) return as_number(evalf(x));
    if (auto it = memo.find(node_of(x)); it != memo.end()) return it->second;  // symbols too: a map lookup
    if (symbolic::is_symbol(x)) {
      auto it = at.find(x);
      std::optional<numeric> v;
      if (it != at.end()) v = as_number(evalf(it->second));
      memo.emplace(node_of(x), v);
      return v;
    }
    if (x.nops() == 0) return as_number(evalf(x));  // a constant
    if (kept)
      if (const numeric* value = kept->find(x)) return *value;
    std::optional<numeric> v;
    if (symbolic::is_add(x) || symbolic::is_mul(x)) {
      const bool product = symbolic::is_mul(x);
      const auto& pairs = pairs_of(x);
      // Numbers only: no expression objects built (a product's exponents are numbers, a sum's coefficients too).
      numeric acc = product ? numeric(1) : numeric(0);
      bool ok = true;
      for (const auto& p : pairs) {
        auto r = self(self, p.rest);
        if (!r) { ok = false; break; }
        const numeric& c = ex_to<numeric>(p.coeff);
        if (product) acc = acc * (c.is_equal(numeric(1)) ? *r : r->power(c));
        else acc = acc + *r * c;
      }
      if (ok && x.nops() > pairs.size()) {  // the numeric overall coefficient
        const numeric& oc = ex_to<numeric>(x.op(x.nops() - 1));
        acc = product ? acc * oc : acc + oc;
      }
      if (ok) v = as_number(evalf(acc));
    } else if (symbolic::is_power(x)) {
      auto b = self(self, x.op(0)), k = self(self, x.op(1));
      if (b && k) v = as_number(evalf(pow(*b, *k)));
    } else if (is_select(x)) {
      // The branch the comparison takes, only: the other may have a pole here (the closed form beside its
      // Taylor series at 0), which must not make the whole select fail.
      // (At a sample point a kernel's real values may be complex; their real parts decide there.)
      auto a = self(self, x.op(0)), b = self(self, x.op(1));
      if (a && b)
        v = self(self, x.op(select_holds(select_operator(x), a->real().to_double(), b->real().to_double()) ? 2 : 3));
    } else if (is_a<function>(x)) {
      exvector args;
      bool ok = true;
      for (size_t i = 0; i < x.nops() && ok; ++i) {
        auto a = self(self, x.op(i));
        if (a) args.push_back(*a);
        else ok = false;
      }
      if (ok) v = as_number(evalf(function(ex_to<function>(x).get_serial(), args)));
    }
    memo.emplace(node_of(x), v);
    if (kept && v && (x.nops() > 8 || (symbolic::is_power(x) && !(symbolic::is_numeric(x.op(1)) && ex_to<numeric>(x.op(1)).is_integer()))))
      kept->keep(x, *v);
    return v;
  };
  return eval(eval, e);
}

GiNaC::ex DagSubs::operator()(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (symbolic::is_symbol(e)) {
    auto it = at_.find(e);
    return it == at_.end() ? e : it->second;
  }
  if (e.nops() == 0) return e;
  // Sums, products, powers and function calls are rebuilt from their substituted operands (what subs
  // does); anything else goes to GiNaC.
  if (!symbolic::is_add(e) && !symbolic::is_mul(e) && !symbolic::is_power(e) && !is_a<function>(e))
    return e.subs(at_, subs_options::no_pattern);
  auto it = memo_.find(node_of(e));
  if (it != memo_.end()) return it->second.second;
  struct Op : map_function {
    DagSubs& self;
    explicit Op(DagSubs& s) : self(s) {}
    ex operator()(const ex& x) override { return self(x); }
  } op(*this);
  ex r = e.map(op);
  memo_.emplace(node_of(e), std::make_pair(e, r));
  return r;
}

}  // namespace cgagen::symbolic
