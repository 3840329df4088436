// The products stage: the expander's view of a script's multivector products as *words*.
//
// The geometric and outer products are associative, and the reverse turns a product around
// (~(A B) = ~B ~A). So a chain such as `(R4*R3*T2*R1) * L * ~(R4*R3*T2*R1)` is, whatever its parentheses, the
// word R4 R3 T2 R1 L ~R1 ~T2 ~R3 ~R4 over its operands. Evaluating it left to right, as the parser groups it,
// shares nothing with `R3*T2*R1` computed two lines before and expands both halves of the sandwich as
// general products of unnamed sums. This stage instead:
//  - hash-conses operands by value: equal multivectors are one atom, and the reverse of a known value is
//    that atom reversed; a name bound to a word stands for its word (V3 = R3*T2*R1 makes V3 that word);
//  - applies a versor as one operation: P m ~P with P a product is the sandwich of m by P, with P bound
//    once to a value of the kernel (a temporary), so ~P is its reverse and costs nothing;
//  - reuses what was computed: the longest part of a word that an earlier statement or sandwich already
//    bound is taken as that value (R4*R3*T2*R1 as R4*(R3*T2*R1)), reversed where the word has its reverse.
// The choice never changes a result (products are exact and associative); the expander's cost model still
// decides, per product, what is expanded and what is bound. docs/generator.md, "Products", has the worked
// example.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "algebra/products.hpp"
#include "expand/kernel.hpp"
#include "front/ast.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::expand_words {

using symbolic::Multivector;

// One factor of a word: a hash-consed operand, possibly reversed.
struct Atom {
  int id = 0;
  bool reversed = false;
  friend bool operator==(Atom a, Atom b) { return a.id == b.id && a.reversed == b.reversed; }
  friend bool operator<(Atom a, Atom b) { return a.id != b.id ? a.id < b.id : a.reversed < b.reversed; }
};
using Word = std::vector<Atom>;

// ~(a b c) = ~c ~b ~a.
Word reversed(const Word& w);

// What the stage asks of the expander.
class Host {
 public:
  // The product a b of the given kind, with the cost model's binding of costly operands.
  virtual Multivector multiply(algebra::ProductKind kind, const Multivector& a, const Multivector& b,
                               front::SourceLoc loc) = 0;
  // v bound to a value of the kernel named `name` (empty: the host names it, and sets `name`); returns the
  // reference to it (one symbol per blade).
  virtual Multivector bind_word(std::string& name, const Multivector& v, front::SourceLoc loc) = 0;

 protected:
  ~Host() = default;
};

class Products {
 public:
  // The atom of an operand; `name` is how messages and temporaries call it (a script name, else empty).
  Atom atom(const Multivector& v, const std::string& name);
  // The atom's word in products of `kind`: the word its value was remembered as (through names bound to
  // words), else the atom alone.
  Word expand(Atom a, algebra::ProductKind kind) const;
  // The value of word w (not empty) of products of the given kind; `statement`: w is the whole value of a
  // statement, which the expander binds and remember()s itself.
  Multivector evaluate(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host,
                       bool statement = false);
  // A statement `name = w;` was recorded with the value `reference`: later words reuse it, and the name
  // stands for w where it is read.
  void remember(algebra::ProductKind kind, const Word& w, const Multivector& reference, const std::string& name);

  // The products named once and reused, in order of naming (those used at least once).
  std::vector<SharedProduct> report() const;

 private:
  struct Known {
    Multivector value;
    std::string name;
    std::optional<std::pair<algebra::ProductKind, Word>> definition;  // the word this value was bound as
  };
  struct Cached {
    Multivector reference;
    size_t report = 0;  // index into shared_
  };
  using Key = std::pair<algebra::ProductKind, Word>;

  std::optional<int> find(const Multivector& v) const;
  int add(const Multivector& v, const std::string& name);
  Multivector value(Atom a) const;
  std::string text(const Word& w) const;
  std::string temp_name(const Word& w) const;
  // The cached value of w or of its reverse, counting a use.
  std::optional<Multivector> lookup(algebra::ProductKind kind, const Word& w);
  void cache(algebra::ProductKind kind, const Word& w, const Multivector& reference, const std::string& name,
             bool bound);
  // w's value bound to a value of the kernel and remembered (a single factor as it is).
  Multivector bound(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host);
  Multivector left_to_right(algebra::ProductKind kind, const Word& w, front::SourceLoc loc, Host& host);

  std::vector<Known> known_;
  std::unordered_multimap<size_t, int> by_hash_;
  std::map<Key, Cached> cache_;
  std::vector<SharedProduct> shared_;
};

}  // namespace cgagen::expand_words
