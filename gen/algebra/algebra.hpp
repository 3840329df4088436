// An Algebra value: which geometric algebra the generator compiles. It holds
//   - the user basis vector names (what scripts write: e1, einf, e0, ...), in the user's order;
//   - a diagonal basis with its metric (+1, -1, 0);
//   - each user vector as a combination of diagonal ones, and each diagonal vector over the user ones;
//   - the blade order used for outputs and arrays: by grade, then lexicographic in the user vector order
//     (the order CGA has always had, blade.hpp), with blade i's bitmap over the user vectors.
// Products of two user blades are worked out on demand from bitmaps and the diagonal metric, the basis
// change applied sparsely, and cached per pair actually used: no 2^n x 2^n table is ever built, so ccga
// (16 vectors, 65,536 blades) works for sparse scripts.
//
// The value travels with the work: expand() takes it, a Kernel and an opt::Program carry it, and expand(),
// optimize(), stage(), emit() and the reports install it as their thread's current algebra (Using) for
// their duration. The free functions of blade.hpp and products.hpp answer for that current algebra, so
// kernels of different algebras can be compiled side by side in one process. (Not on several threads at
// once: GiNaC's reference counts are not atomic.)
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "algebra/products.hpp"

namespace cgagen::algebra {

using Bits = std::uint32_t;  // a blade as a bitmap over the user (or diagonal) vectors; up to 16 vectors

// A sparse combination of blades (bitmap -> exact coefficient).
using BladeCombination = std::map<Bits, Rational>;

// A located problem in an algebra definition file (file:line: error: ...).
struct AlgebraError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The raw description an Algebra is made from (what a definition.csv holds).
struct AlgebraSpec {
  std::string name;                          // "cga", "3dpga", or the file's stem
  std::vector<std::string> user;             // user basis vector names (without "1")
  std::vector<std::string> diagonal;         // diagonal basis vector names
  std::vector<int> metric;                   // per diagonal vector: +1, -1 or 0
  // user vector k over the diagonal vectors, diagonal vector d over the user vectors (index -> coefficient)
  std::vector<std::map<int, Rational>> user_in_diagonal, diagonal_in_user;
  bool cga_idents = false;  // the built-in CGA: keep its identifiers exactly (e1inf, einf0)
};

class Algebra {
 public:
  static constexpr int kMaxVectors = 16;
  explicit Algebra(AlgebraSpec spec);  // throws AlgebraError when the spec is not a basis

  const std::string& name() const { return spec_.name; }
  int dimension() const { return static_cast<int>(spec_.user.size()); }
  int blade_count() const { return 1 << dimension(); }
  const std::vector<std::string>& vector_names() const { return spec_.user; }
  const AlgebraSpec& spec() const { return spec_; }
  bool degenerate() const;         // some diagonal vector squares to 0 (PGA)
  bool diagonal_is_user() const { return identity_; }

  // Blade order (see the top of this file).
  Bits bits(BladeIndex i) const;
  BladeIndex index(Bits b) const;
  int grade(BladeIndex i) const;
  const std::string& blade_name(BladeIndex i) const;   // "1", "e0^e1^e2"
  const std::string& blade_ident(BladeIndex i) const;  // "s", "e012"; identifier-safe
  std::optional<SignedBlade> parse_blade(std::string_view text) const;
  // Index of the user vector called name, or -1.
  int vector_index(std::string_view name) const;

  // The nonzero terms of blade a (op) blade b, in increasing blade order (cached per pair).
  const std::vector<ProductTerm>& product(ProductKind kind, BladeIndex a, BladeIndex b) const;
  // The pseudoscalar's inverse, as a coefficient on the last blade; nullopt when degenerate.
  std::optional<Rational> inverse_pseudoscalar() const;

 private:
  const BladeCombination& user_blade_in_diagonal(Bits b) const;
  const BladeCombination& diagonal_blade_in_user(Bits b) const;

  AlgebraSpec spec_;
  bool identity_ = false;
  std::vector<Bits> bits_;          // index -> bitmap
  std::vector<BladeIndex> index_;   // bitmap -> index
  mutable std::unordered_map<BladeIndex, std::string> names_, idents_;
  mutable std::unordered_map<Bits, BladeCombination> up_, down_;
  mutable std::unordered_map<std::uint64_t, std::vector<ProductTerm>> products_;
};

// The algebras built in: Gaalop's eleven names (definedAlgebras.txt), our own definitions from the math.
const std::vector<std::string>& builtin_names();
// A built-in by name; nullptr when unknown.
std::shared_ptr<const Algebra> builtin(const std::string& name);
// Parses Gaalop's definition.csv format (five lines, see docs/generator.md). `text` is the file's content,
// `file` its name for messages; errors are AlgebraError "file:line: error: ...".
AlgebraSpec parse_definition(const std::string& text, const std::string& file, const std::string& name);
// NAME (built-in) or a path to a definition.csv; throws AlgebraError.
std::shared_ptr<const Algebra> load(const std::string& name_or_file);

// The thread's current algebra (default: the built-in CGA).
const Algebra& current();
std::shared_ptr<const Algebra> current_shared();
void use(std::shared_ptr<const Algebra> a);
// Sets the thread's algebra for a scope, restoring the previous one after; a null `a` keeps the current one.
class Using {
 public:
  explicit Using(std::shared_ptr<const Algebra> a);
  ~Using();
  Using(const Using&) = delete;
  Using& operator=(const Using&) = delete;

 private:
  std::shared_ptr<const Algebra> previous_;
};

}  // namespace cgagen::algebra
