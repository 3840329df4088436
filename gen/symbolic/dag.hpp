// Walks over a GiNaC expression as the DAG it is. Values substituted into each other share most of their
// subexpressions; GiNaC's preorder iterator, subs() and evalf() treat them as trees, which costs time
// exponential in the depth of the substitution chain (Gaalop's GPS trilateration script).
#pragma once

#include <ginac/ginac.h>

#include <cstddef>
#include <optional>
#include <set>
#include <typeinfo>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace cgagen::symbolic {

// The node's identity: the shared object ex points to.
inline const GiNaC::basic* node_of(const GiNaC::ex& e) { return &GiNaC::ex_to<GiNaC::basic>(e); }

// A value per expression node, kept between walks. Each entry holds its node alive, so the node's address
// is never reused for another node while the entry lives; the table is emptied when it reaches
// kMaxEntries, which bounds the memory of a very large script.
template <class T>
class NodeTable {
 public:
  static constexpr std::size_t kMaxEntries = 20000;
  const T* find(const GiNaC::ex& e) const {
    auto it = entries_.find(node_of(e));
    return it == entries_.end() ? nullptr : &it->second.second;
  }
  void keep(const GiNaC::ex& e, T value) {
    if (entries_.size() >= kMaxEntries) entries_.clear();
    entries_.emplace(node_of(e), std::make_pair(e, std::move(value)));
  }
  std::size_t size() const { return entries_.size(); }

 private:
  std::unordered_map<const GiNaC::basic*, std::pair<GiNaC::ex, T>> entries_;
};

// The class of a node, for hot walks. GiNaC's is_a<T> is a dynamic_cast, which costs a few hundred
// instructions here, most of them strcmp of type names (Debian's libstdc++ compares type_info objects by
// name). The classes nearly every node belongs to are recognized first by the identity of their type_info;
// anything else (another class, or a type_info not shared across libraries) asks is_a, so the answers are
// is_a's: Symbol for every symbol class (realsymbol), Function for every function.
enum class Kind : unsigned char { Numeric, Symbol, Add, Mul, Power, Function, Constant, Other };
inline Kind kind_of(const GiNaC::ex& e) {
  const std::type_info* t = &typeid(*node_of(e));
  if (t == &typeid(GiNaC::mul)) return Kind::Mul;
  if (t == &typeid(GiNaC::add)) return Kind::Add;
  if (t == &typeid(GiNaC::realsymbol) || t == &typeid(GiNaC::symbol)) return Kind::Symbol;
  if (t == &typeid(GiNaC::numeric)) return Kind::Numeric;
  if (t == &typeid(GiNaC::power)) return Kind::Power;
  if (GiNaC::is_a<GiNaC::numeric>(e)) return Kind::Numeric;
  if (GiNaC::is_a<GiNaC::symbol>(e)) return Kind::Symbol;
  if (GiNaC::is_a<GiNaC::add>(e)) return Kind::Add;
  if (GiNaC::is_a<GiNaC::mul>(e)) return Kind::Mul;
  if (GiNaC::is_a<GiNaC::power>(e)) return Kind::Power;
  if (GiNaC::is_a<GiNaC::function>(e)) return Kind::Function;
  if (GiNaC::is_a<GiNaC::constant>(e)) return Kind::Constant;
  return Kind::Other;
}
inline bool is_numeric(const GiNaC::ex& e) { return kind_of(e) == Kind::Numeric; }
inline bool is_symbol(const GiNaC::ex& e) { return kind_of(e) == Kind::Symbol; }
inline bool is_add(const GiNaC::ex& e) { return kind_of(e) == Kind::Add; }
inline bool is_mul(const GiNaC::ex& e) { return kind_of(e) == Kind::Mul; }
inline bool is_power(const GiNaC::ex& e) { return kind_of(e) == Kind::Power; }
// A symbol, a number or a constant (Pi): what the optimizer treats as atomic.
inline bool is_symbol_number_or_constant(const GiNaC::ex& e) {
  const Kind k = kind_of(e);
  return k == Kind::Symbol || k == Kind::Numeric || k == Kind::Constant;
}
// Whether e has more than `limit` nodes counted as a tree (a shared subtree once per use), stopping at the
// limit: bounded time however large the DAG. What decides where a tree walk (GiNaC's evalf) is affordable
// and where a long expression is bound to a temporary.
inline bool tree_larger_than(const GiNaC::ex& e, std::size_t limit) {
  std::vector<GiNaC::ex> todo{e};
  std::size_t seen = 0;
  while (!todo.empty()) {
    const GiNaC::ex x = todo.back();
    todo.pop_back();
    if (++seen > limit) return true;
    for (std::size_t i = 0; i < x.nops(); ++i) todo.push_back(x.op(i));
  }
  return false;
}

// is_a<expairseq>: GiNaC's sums and products (pairs_of applies).
inline bool is_add_or_mul(const GiNaC::ex& e) {
  const Kind k = kind_of(e);
  return k == Kind::Add || k == Kind::Mul || (k == Kind::Other && GiNaC::is_a<GiNaC::expairseq>(e));
}

// Hash and equality of expressions as values (GiNaC's cached hash; equal expressions hash alike), for
// tables keyed by expression that are only looked up, never iterated, so that their order cannot matter.
// A lookup compares one or two entries, where an ordered map (ex_is_less) compares ~log2(n) along its path.
struct ExHash {
  std::size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};
template <class T>
using ExHashMap = std::unordered_map<GiNaC::ex, T, ExHash, GiNaC::ex_is_equal>;
using ExHashSet = std::unordered_set<GiNaC::ex, ExHash, GiNaC::ex_is_equal>;

// The terms of a sum / factors of a product as GiNaC stores them: (rest, coeff) pairs, coeff a number (a
// term's coefficient, a factor's exponent; the sum's or product's numeric overall coefficient is not among
// them). op(i) rebuilds coeff*rest or rest^coeff as a fresh object at each call, so a walk through op()
// allocates at every node and never meets a shared node twice; the stored rests are the shared nodes.
namespace detail {
struct SeqAccess : GiNaC::expairseq {
  static const GiNaC::epvector& seq_of(const GiNaC::expairseq& e) { return e.*(&SeqAccess::seq); }
};
}  // namespace detail
// e must be a sum or a product (is_a<expairseq>).
inline const GiNaC::epvector& pairs_of(const GiNaC::ex& e) {
  return detail::SeqAccess::seq_of(GiNaC::ex_to<GiNaC::expairseq>(e));
}

// Calls f(node) once per distinct node of e reachable through op() (the nodes the preorder iterator
// visits, each shared one once); stops and returns true as soon as f returns true.
template <class F>
bool visit_nodes_once(const GiNaC::ex& e, F&& f) {
  std::unordered_set<const GiNaC::basic*> seen;
  std::vector<GiNaC::ex> keep;  // keeps visited nodes (op() may make fresh ones) alive: no address reuse
  std::vector<GiNaC::ex> stack{e};
  while (!stack.empty()) {
    GiNaC::ex x = std::move(stack.back());
    stack.pop_back();
    if (!seen.insert(node_of(x)).second) continue;
    keep.push_back(x);
    if (f(x)) return true;
    for (std::size_t i = x.nops(); i-- > 0;) stack.push_back(x.op(i));
  }
  return false;
}

// Adds the symbols of e to `symbols`, each shared node visited once.
void collect_symbols_into(const GiNaC::ex& e, std::set<GiNaC::ex, GiNaC::ex_is_less>& symbols);

// For values computed lazily along a chain of definitions (a symbol's value at a probe point needs the
// values of the symbols its definition uses): calls define(s) once for every symbol s that e uses, directly
// or through definitions, while pending(s) holds, the symbols a definition uses before the symbol itself.
// definition(s) gives s's definition, over symbols defined before s (no cycles); define(s) must make
// pending(s) false. Iterative: chains of thousands of statements need no deep recursion.
template <class Pending, class Definition, class Define>
void define_dependencies_first(const GiNaC::ex& e, Pending&& pending, Definition&& definition, Define&& define) {
  std::vector<std::pair<GiNaC::ex, bool>> stack;  // (symbol, its dependencies pushed already)
  auto push_pending_symbols = [&](const GiNaC::ex& x) {
    std::set<GiNaC::ex, GiNaC::ex_is_less> symbols;
    collect_symbols_into(x, symbols);
    for (const GiNaC::ex& s : symbols)
      if (pending(s)) stack.emplace_back(s, false);
  };
  push_pending_symbols(e);
  while (!stack.empty()) {
    auto [s, ready] = std::move(stack.back());
    stack.pop_back();
    if (!pending(s)) continue;  // reached twice
    if (ready) {
      define(s);
    } else {
      stack.emplace_back(s, true);
      push_pending_symbols(definition(s));
    }
  }
}

// Does e contain a number that is not real (2i from sqrt(-4))? Each shared node once, over the stored
// pairs of sums and products (no operand rebuilt); the numbers are those a walk through op() meets.
bool has_nonreal_number(const GiNaC::ex& e);

// Does e have a power with a negative numeric exponent (a denominator)? Each shared node once.
bool has_negative_power(const GiNaC::ex& e);

// The number of symbol occurrences of e counted as a tree (what a preorder walk counts), in time linear in
// the DAG.
std::size_t tree_symbol_count(const GiNaC::ex& e);

// evalf(e.subs(at)) for a map from symbols to numbers, computed on the stored nodes (each shared node
// once, no expression built): a number, possibly complex, or nullopt where some node does not evaluate to
// a number (a symbol without a value, a function GiNaC leaves unevaluated); callers then ask GiNaC. Throws
// at a pole, as subs/evalf would.
//
// `kept`, when given, holds the values of large nodes (sums and products of more than 8 operands,
// non-integer powers) between calls with the same map: a normalized value's root of a large sum sits
// under every one of its coefficients. Only valid while the values of the symbols those nodes use stay
// the same; entries hold their node alive (no address reuse).
using KeptValues = NodeTable<GiNaC::numeric>;
std::optional<GiNaC::numeric> evalf_at(const GiNaC::ex& e, const GiNaC::exmap& at, KeptValues* kept = nullptr);

// e.subs(at, subs_options::no_pattern) for a map from symbols to values, computing each shared node once.
// Throws what subs would throw (a division by zero at a pole).
class DagSubs {
 public:
  explicit DagSubs(const GiNaC::exmap& at) : at_(at) {}
  GiNaC::ex operator()(const GiNaC::ex& e);

 private:
  const GiNaC::exmap& at_;
  std::unordered_map<const GiNaC::basic*, std::pair<GiNaC::ex, GiNaC::ex>> memo_;  // node -> (node, value)
};

}  // namespace cgagen::symbolic
