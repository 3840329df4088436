// The products stage (words.hpp): hash-consed operands, sandwiches, and reuse of bound words.
#include "expand/words.hpp"

#include <algorithm>

namespace cgagen::expand_words {

namespace {

// A word longer than this is not expanded further through the names it reads: the search for reusable parts
// is quadratic in the word's length, and a chain `M = M*R` repeated thousands of times would otherwise carry
// its whole history in every statement. (The value is the same; only reuse past this length is not seen.)
constexpr size_t kMaxWord = 48;
// From this length on, a word with no part to reuse is evaluated by halves (evaluate()); shorter ones left to
// right, as written, which every bundled script's products are.
constexpr size_t kHalvedWord = 5;

size_t hash_of(const Multivector& v) {
  size_t h = v.terms().size();
  for (const auto& [b, c] : v.terms()) h = h * 1000003u ^ (static_cast<size_t>(b) * 7919u + c.gethash());
  return h;
}

bool same(const Multivector& a, const Multivector& b) {
  if (a.terms().size() != b.terms().size()) return false;
  auto i = a.terms().begin();
  for (auto j = b.terms().begin(); j != b.terms().end(); ++i, ++j)
    if (i->first != j->first || !i->second.is_equal(j->second)) return false;
  return true;
}

}  // namespace

Word reversed(const Word& w) {
  Word r(w.rbegin(), w.rend());
  for (auto& a : r) a.reversed = !a.reversed;
  return r;
}

std::optional<int> Products::find(const Multivector& v) const {
  auto [lo, hi] = by_hash_.equal_range(hash_of(v));
  for (auto it = lo; it != hi; ++it)
    if (same(known_[static_cast<size_t>(it->second)].value, v)) return it->second;
  return std::nullopt;
}

int Products::add(const Multivector& v, const std::string& name) {
  const int id = static_cast<int>(known_.size());
  known_.push_back({v, name, std::nullopt});
  by_hash_.emplace(hash_of(v), id);
  return id;
}

Atom Products::atom(const Multivector& v, const std::string& name) {
  if (auto id = find(v)) {
    Known& k = known_[static_cast<size_t>(*id)];
    if (k.name.empty()) k.name = name;
    return {*id, false};
  }
  // A scalar is its own reverse; anything else may be the reverse of a known value (~R of a read R).
  if (!v.is_scalar())
    if (auto id = find(v.reverse())) return {*id, true};
  return {add(v, name), false};
}

Word Products::expand(Atom a, algebra::ProductKind kind) const {
  const Known& k = known_[static_cast<size_t>(a.id)];
  if (!k.definition || k.definition->first != kind) return {a};
  return a.reversed ? reversed(k.definition->second) : k.definition->second;
}

Multivector Products::value(Atom a) const {
  const Multivector& v = known_[static_cast<size_t>(a.id)].value;
  return a.reversed ? v.reverse() : v;
}

std::string Products::text(const Word& w) const {
  std::string s;
  for (const Atom& a : w) {
    const std::string& n = known_[static_cast<size_t>(a.id)].name;
    s += (s.empty() ? "" : "*") + std::string(a.reversed ? "~" : "") + (n.empty() ? "(...)" : n);
  }
  return s;
}

// "R2_R1" for a short word of named operands (a reversed one as "rR1"); empty otherwise (the expander then
// names the temporary after its statement).
std::string Products::temp_name(const Word& w) const {
  if (w.size() > 4) return "";
  std::string s;
  for (const Atom& a : w) {
    const std::string& n = known_[static_cast<size_t>(a.id)].name;
    if (n.empty()) return "";
    s += (s.empty() ? "" : "_") + std::string(a.reversed ? "r" : "") + n;
  }
  return s;
}

std::optional<Multivector> Products::lookup(algebra::ProductKind kind, const Word& w) {
  auto it = cache_.find({kind, w});
  if (it == cache_.end()) return std::nullopt;
  ++shared_[it->second.report].uses;
  return it->second.reference;
}

void Products::cache(algebra::ProductKind kind, const Word& w, const Multivector& reference, const std::string& name,
                     bool bound) {
  if (cache_.count({kind, w})) return;
  const size_t report = shared_.size();
  shared_.push_back({name, text(w), 0, bound});
  cache_[{kind, w}] = {reference, report};
  if (kind == algebra::ProductKind::Geometric || kind == algebra::ProductKind::Outer)
    cache_.emplace(Key{kind, reversed(w)}, Cached{reference.reverse(), report});
}

void Products::remember(algebra::ProductKind kind, const Word& w, const Multivector& reference,
                        const std::string& name) {
  if (w.size() < 2 || reference.is_zero()) return;
  const Atom a = atom(reference, name);
  Known& k = known_[static_cast<size_t>(a.id)];
  if (!a.reversed && !k.definition && w.size() <= kMaxWord) k.definition = {kind, w};
  cache(kind, w, reference, name, false);
}

Multivector Products::left_to_right(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host) {
  Multivector acc = value(w.front());
  for (size_t i = 1; i < w.size(); ++i) acc = host.multiply(kind, acc, value(w[i]), loc);
  return acc;
}

Multivector Products::bound(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host) {
  if (w.size() == 1) return value(w.front());
  if (auto c = lookup(kind, w)) return *c;
  std::string name = temp_name(w);
  const Multivector v = host.bind_word(name, evaluate(kind, w, loc, host), loc);
  cache(kind, w, v, name, true);
  return v;
}

Multivector Products::evaluate(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host,
                               bool statement) {
  const size_t n = w.size();
  if (n == 1) return value(w.front());
  if (auto c = lookup(kind, w)) return *c;

  // A sandwich P m ~P: P bound once (a product of several factors) and applied as a versor.
  if (kind == algebra::ProductKind::Geometric) {
    size_t k = 0;
    while (k < (n - 1) / 2 && w[k].id == w[n - 1 - k].id && w[k].reversed != w[n - 1 - k].reversed) ++k;
    if (k >= 1) {
      const Word p(w.begin(), w.begin() + static_cast<long>(k));
      Multivector pv;
      pv = bound(kind, p, loc, host);
      const Word middle(w.begin() + static_cast<long>(k), w.end() - static_cast<long>(k));
      const Multivector m = evaluate(kind, middle, loc, host);
      return host.multiply(kind, host.multiply(kind, pv, m, loc), pv.reverse(), loc);
    }
  }

  // A power x x ... x: its square first, bound where it has fewer blades than x and is not a constant (a
  // line's square is a scalar and a 4-vector), so that the higher powers are products of that short value
  // and not polynomials in x's coefficients (the 4th-order Taylor series of a rotor about a line: 44 ops
  // instead of 104). A statement that is the square itself is bound by the expander already.
  if (kind == algebra::ProductKind::Geometric && !(n == 2 && statement) &&
      std::all_of(w.begin(), w.end(), [&](Atom a) { return a == w[0]; })) {
    const Word square(2, w[0]);
    if (!cache_.count({kind, square})) {
      const Multivector x = value(w[0]);
      const Multivector sq = host.multiply(kind, x, x, loc);
      if (sq.terms().size() >= x.terms().size() ||
          std::all_of(sq.terms().begin(), sq.terms().end(), [](const auto& t) { return GiNaC::is_a<GiNaC::numeric>(t.second); })) {
        if (n == 2) return sq;
      } else {
        std::string name = temp_name(square);
        const Multivector v = host.bind_word(name, sq, loc);
        cache(kind, square, v, name, true);
        if (n == 2) return v;
      }
    }
  }

  // The longest part already bound (leftmost among equals), then what is left on either side.
  size_t best_len = 0, best_at = 0;
  for (size_t i = 0; i + 2 <= n; ++i)
    for (size_t len = std::min(n - i, n - 1); len >= 2 && len > best_len; --len)
      if (cache_.count({kind, Word(w.begin() + static_cast<long>(i), w.begin() + static_cast<long>(i + len))})) {
        best_len = len;
        best_at = i;
        break;
      }
  if (best_len == 0) {
    // A long word with nothing to reuse (a power R*R*...*R, a product of many distinct factors) goes by halves,
    // each half bound and remembered: equal halves are computed once, and no coefficient grows into a
    // polynomial of the word's length in its factors' coefficients.
    if (n < kHalvedWord) return left_to_right(kind, w, loc, host);
    const auto mid = w.begin() + static_cast<long>(n / 2);
    return host.multiply(kind, bound(kind, Word(w.begin(), mid), loc, host), bound(kind, Word(mid, w.end()), loc, host),
                         loc);
  }
  const auto at = w.begin() + static_cast<long>(best_at);
  Multivector r = *lookup(kind, Word(at, at + static_cast<long>(best_len)));
  if (best_at > 0) r = host.multiply(kind, evaluate(kind, Word(w.begin(), at), loc, host), r, loc);
  if (best_at + best_len < n)
    r = host.multiply(kind, r, evaluate(kind, Word(at + static_cast<long>(best_len), w.end()), loc, host), loc);
  return r;
}

std::vector<SharedProduct> Products::report() const {
  std::vector<SharedProduct> r;
  for (const auto& s : shared_)
    if (s.uses > 0 || s.bound) r.push_back(s);
  return r;
}

}  // namespace cgagen::expand_words
