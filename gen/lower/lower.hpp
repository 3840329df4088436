// How a GiNaC expression becomes straight-line code, shared by the emitters (which print it) and the op
// counter (which costs it), so that --stats always describes exactly the printed code. Its own stage
// (cgagen_lower, below both opt and emit, on symbolic only); its names stay in cgagen::opt, where the
// programs they describe live.
//
// Rules: a sum of n terms costs n-1 additions (a term with a negative coefficient is printed as a
// subtraction, and terms are ordered positive-first so a leading negation is rare); a product is
// `c * f1 * f2 ... / (d1 * d2 ...)` where integer powers are spelled out as repeated factors (x^3 = x*x*x,
// GLSL's pow is undefined for negative bases), a numeric factor other than +-1 costs one multiplication
// and a denominator one division; x^(1/2) is sqrt(x), other non-integer powers pow(x, p/q): one call each;
// functions (sin, cos, abs, atan2, ...) one call each; constants are free (the compiler folds them).
// Orders are by a canonical text key, never by GiNaC's internal (symbol-serial dependent) order, so the
// same kernel gives the same text in any process and on any run.
#pragma once

#include <ginac/ginac.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "symbolic/dag.hpp"

namespace cgagen::opt {

struct OpCounts {
  long add = 0, mul = 0, div = 0, call = 0;
  OpCounts& operator+=(const OpCounts& o) {
    add += o.add, mul += o.mul, div += o.div, call += o.call;
    return *this;
  }
  // The figure the optimizer minimizes: divisions and calls weigh as several multiplications.
  long weighted() const { return add + mul + 4 * div + 8 * call; }
  long total() const { return add + mul + div + call; }
  friend bool operator==(const OpCounts&, const OpCounts&) = default;
};

// Names of symbols, used for canonical keys and printing. Symbols not in the map print as GiNaC names.
using SymbolNames = std::map<GiNaC::ex, std::string, GiNaC::ex_is_less>;

// A serial-independent text key of an expression (sorted sums and products), memoized. GiNaC chooses the
// sign of a sum inside a product by its internal term order ((a-b)*x or -(b-a)*x), so keys are built from
// a sign and a magnitude: a sum is oriented so that its first term (by magnitude key) is positive.
class CanonicalKeys {
 public:
  explicit CanonicalKeys(const SymbolNames& names) : names_(names) {}
  const std::string& key(const GiNaC::ex& e);  // sign + magnitude key
  int sign(const GiNaC::ex& e);                // -1 when e prints with a leading minus, else +1
  const std::string& magnitude(const GiNaC::ex& e);  // the key of sign(e) * e
  // A sign-independent strict order (magnitude, then full key) for deterministic traversals.
  bool less(const GiNaC::ex& a, const GiNaC::ex& b);
 private:
  struct Entry {
    int sign;
    std::string magnitude, full;
  };
  const Entry& entry(const GiNaC::ex& e);
  const SymbolNames& names_;
  symbolic::ExHashMap<Entry> memo_;  // references to entries stay valid as it grows
};

// One factor of a product: base^exponent with exponent >= 1 spelled out as repeated products.
struct Factor {
  GiNaC::ex base;
  int exponent = 1;
};

// e as coeff * num... / den...  (for a non-product e: coeff 1, num {e}). Sum factors are oriented by
// CanonicalKeys (their sign moved into coeff), so the printed text does not depend on GiNaC's choice.
struct ProductParts {
  GiNaC::numeric coeff = 1;
  std::vector<Factor> num;
  std::vector<Factor> den;
};
ProductParts split_product(const GiNaC::ex& e, CanonicalKeys& keys);

// True when e prints with a leading minus (keys.sign(e) < 0).
bool is_negative_term(const GiNaC::ex& e, CanonicalKeys& keys);

// The terms of a sum in printing order: non-negative terms first, then by canonical key.
std::vector<GiNaC::ex> sum_terms(const GiNaC::ex& sum, CanonicalKeys& keys);

// Children of e in canonical order (for deterministic traversals).
std::vector<GiNaC::ex> ordered_children(const GiNaC::ex& e, CanonicalKeys& keys);

// The cost of printing e (its own operations; symbols cost nothing).
OpCounts count_ops(const GiNaC::ex& e, CanonicalKeys& keys);

// e rebuilt so that every sum that is a factor of a product or the base of an integer power is oriented
// (keys.sign(sum) > 0), its sign moved into the product's coefficient (odd powers) or dropped (even powers).
// A top-level sum keeps its sign (GiNaC distributes -1 over a lone sum). GiNaC's choice between (a-b)*x and
// -(b-a)*x depends on its hash order, which moves with ASLR; after this the tree depends only on the keys.
GiNaC::ex orient_sums(const GiNaC::ex& e, CanonicalKeys& keys);

// True for a power with a non-negative, non-integer rational exponent 1/2 (printed as sqrt).
bool is_sqrt(const GiNaC::ex& e);

}  // namespace cgagen::opt
