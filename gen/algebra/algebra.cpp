// The Algebra value (see algebra.hpp): blade order, names, sparse cached products, the definition.csv
// parser and the eleven built-in algebras.
#include "algebra/algebra.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>

namespace cgagen::algebra {
namespace {

// Sign of moving the vectors of b past those of a into increasing order (one minus per swap).
int reorder_sign(Bits a, Bits b) {
  a >>= 1;
  int swaps = 0;
  while (a) {
    swaps += std::popcount(a & b);
    a >>= 1;
  }
  return (swaps & 1) ? -1 : 1;
}

// The outer product of two sparse combinations of blades over one basis.
BladeCombination outer(const BladeCombination& x, const BladeCombination& y) {
  BladeCombination r;
  for (const auto& [a, ca] : x)
    for (const auto& [b, cb] : y) {
      if (a & b) continue;
      Rational& slot = r[a | b];
      slot = slot + Rational(reorder_sign(a, b)) * ca * cb;
    }
  for (auto it = r.begin(); it != r.end();) it = it->second.is_zero() ? r.erase(it) : std::next(it);
  return r;
}

// Expands the blade `bits` (an outer product of vectors in increasing order) over another basis, each
// vector k of which is `vectors[k]` there.
BladeCombination expand_blade(Bits bits, const std::vector<std::map<int, Rational>>& vectors) {
  BladeCombination r{{0, Rational(1)}};
  for (int k = 0; k < 32 && (bits >> k); ++k) {
    if (!(bits & (1u << k))) continue;
    BladeCombination v;
    for (const auto& [d, c] : vectors[k]) v[1u << d] = c;
    r = outer(r, v);
  }
  return r;
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

}  // namespace

Algebra::Algebra(AlgebraSpec spec) : spec_(std::move(spec)) {
  const int n = dimension();
  if (n < 1 || n > kMaxVectors)
    throw AlgebraError("algebra '" + spec_.name + "': " + std::to_string(n) + " basis vectors; cgagen takes 1 to " +
                       std::to_string(kMaxVectors));
  if (spec_.diagonal.size() != spec_.user.size() || spec_.metric.size() != spec_.diagonal.size() ||
      spec_.user_in_diagonal.size() != spec_.user.size() || spec_.diagonal_in_user.size() != spec_.diagonal.size())
    throw AlgebraError("algebra '" + spec_.name + "': the user and diagonal bases differ in size");
  identity_ = spec_.user == spec_.diagonal;
  for (int k = 0; identity_ && k < n; ++k)
    identity_ = spec_.user_in_diagonal[k] == std::map<int, Rational>{{k, Rational(1)}} &&
                spec_.diagonal_in_user[k] == std::map<int, Rational>{{k, Rational(1)}};
  // Blade order: by grade, then lexicographic in the user vector order (combinations in lexicographic order).
  index_.assign(std::size_t(1) << n, 0);
  std::vector<int> pick;
  std::function<void(int, int)> choose = [&](int from, int left) {
    if (left == 0) {
      Bits b = 0;
      for (int k : pick) b |= 1u << k;
      index_[b] = static_cast<BladeIndex>(bits_.size());
      bits_.push_back(b);
      return;
    }
    for (int k = from; k <= n - left; ++k) {
      pick.push_back(k);
      choose(k + 1, left - 1);
      pick.pop_back();
    }
  };
  for (int g = 0; g <= n; ++g) choose(0, g);
}

bool Algebra::degenerate() const { return std::count(spec_.metric.begin(), spec_.metric.end(), 0) > 0; }

Bits Algebra::bits(BladeIndex i) const { return bits_.at(static_cast<std::size_t>(i)); }
BladeIndex Algebra::index(Bits b) const { return index_.at(b); }
int Algebra::grade(BladeIndex i) const { return std::popcount(bits(i)); }

const std::string& Algebra::blade_name(BladeIndex i) const {
  auto it = names_.find(i);
  if (it != names_.end()) return it->second;
  const Bits b = bits(i);
  std::string name;
  for (int k = 0; k < dimension(); ++k)
    if (b & (1u << k)) name += (name.empty() ? "" : "^") + spec_.user[k];
  return names_.emplace(i, name.empty() ? "1" : name).first->second;
}

const std::string& Algebra::blade_ident(BladeIndex i) const {
  auto it = idents_.find(i);
  if (it != idents_.end()) return it->second;
  // Names e<suffix> join their suffixes: e0^e1^e2 -> e012, e1^einf -> e1inf (CGA). Longer suffixes that
  // could run together (ei1^eo1) are joined with '_'; other names are joined whole with '_'.
  bool all_e = true, short_suffixes = true;
  for (const auto& v : spec_.user) {
    all_e = all_e && v.size() > 1 && v[0] == 'e' && is_identifier(v);
    short_suffixes = short_suffixes && v.size() == 2;
  }
  const Bits b = bits(i);
  std::string id;
  for (int k = 0; k < dimension(); ++k) {
    if (!(b & (1u << k))) continue;
    const std::string& v = spec_.user[k];
    if (all_e && (spec_.cga_idents || short_suffixes)) id += (id.empty() ? "e" : "") + v.substr(1);
    else if (all_e) id += (id.empty() ? "e" : "_") + v.substr(1);
    else id += (id.empty() ? "b_" : "_") + v;
  }
  return idents_.emplace(i, id.empty() ? "s" : id).first->second;
}

int Algebra::vector_index(std::string_view name) const {
  for (int k = 0; k < dimension(); ++k)
    if (spec_.user[k] == name) return k;
  return -1;
}

std::optional<SignedBlade> Algebra::parse_blade(std::string_view text) const {
  if (text == "1") return SignedBlade{0, 1};
  std::vector<int> order;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t end = text.find('^', pos);
    if (end == std::string_view::npos) end = text.size();
    int k = vector_index(text.substr(pos, end - pos));
    if (k < 0 || std::find(order.begin(), order.end(), k) != order.end()) return std::nullopt;
    order.push_back(k);
    pos = end + 1;
  }
  // Sign of sorting the vectors into increasing order: one minus per transposition (they anticommute).
  int sign = 1;
  for (size_t a = 0; a < order.size(); ++a)
    for (size_t b = a + 1; b < order.size(); ++b)
      if (order[a] > order[b]) sign = -sign;
  Bits bits = 0;
  for (int k : order) bits |= 1u << k;
  return SignedBlade{index(bits), sign};
}

const BladeCombination& Algebra::user_blade_in_diagonal(Bits b) const {
  auto it = up_.find(b);
  if (it != up_.end()) return it->second;
  return up_.emplace(b, expand_blade(b, spec_.user_in_diagonal)).first->second;
}

const BladeCombination& Algebra::diagonal_blade_in_user(Bits b) const {
  auto it = down_.find(b);
  if (it != down_.end()) return it->second;
  return down_.emplace(b, expand_blade(b, spec_.diagonal_in_user)).first->second;
}

const std::vector<ProductTerm>& Algebra::product(ProductKind kind, BladeIndex a, BladeIndex b) const {
  if (a < 0 || b < 0 || a >= blade_count() || b >= blade_count())
    throw std::out_of_range("blade index out of range");
  const std::uint64_t key = (std::uint64_t(kind) << 40) | (std::uint64_t(a) << 20) | std::uint64_t(b);
  auto found = products_.find(key);
  if (found != products_.end()) return found->second;
  std::vector<ProductTerm> out;
  const int ga = grade(a), gb = grade(b);
  if (kind != ProductKind::Inner || (ga > 0 && gb > 0)) {
    // Over the diagonal basis a blade product is one blade: the XOR of the bitmaps, a reordering sign, and
    // the metric of every shared vector (0 for a null one). The outer product drops shared vectors.
    BladeCombination diag;
    for (const auto& [da, ca] : user_blade_in_diagonal(bits(a)))
      for (const auto& [db, cb] : user_blade_in_diagonal(bits(b))) {
        if (kind == ProductKind::Outer && (da & db)) continue;
        int sign = reorder_sign(da, db);
        for (Bits common = da & db; common && sign; common &= common - 1) sign *= spec_.metric[std::countr_zero(common)];
        if (!sign) continue;
        Rational& slot = diag[da ^ db];
        slot = slot + Rational(sign) * ca * cb;
      }
    std::map<BladeIndex, Rational> user;
    for (const auto& [d, c] : diag) {
      if (c.is_zero()) continue;
      for (const auto& [u, cu] : diagonal_blade_in_user(d)) {
        Rational& slot = user[index(u)];
        slot = slot + c * cu;
      }
    }
    const int want = ga > gb ? ga - gb : gb - ga;
    for (const auto& [i, c] : user)
      if (!c.is_zero() && (kind != ProductKind::Inner || grade(i) == want)) out.push_back({i, c});
  }
  return products_.emplace(key, std::move(out)).first->second;
}

std::optional<Rational> Algebra::inverse_pseudoscalar() const {
  if (degenerate()) return std::nullopt;
  const BladeIndex top = blade_count() - 1;
  const auto& sq = product(ProductKind::Geometric, top, top);
  if (sq.size() != 1 || sq[0].blade != 0) return std::nullopt;
  return Rational(1) / sq[0].coeff;
}

// ---- definition.csv ------------------------------------------------------------------------------------

namespace {

struct CsvReader {
  std::string file;
  [[noreturn]] void fail(int line, const std::string& msg) const {
    throw AlgebraError(file + ":" + std::to_string(line) + ": error: " + msg);
  }
};

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  if (trim(s).empty()) return out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) out.push_back(trim(item));
  return out;
}

// "0.5", "2", "1/2" exactly; decimals of at most 9 fractional digits (cgagen computes exactly).
Rational parse_rational(const std::string& text, const CsvReader& r, int line) {
  auto slash = text.find('/');
  if (slash != std::string::npos) {
    Rational a = parse_rational(text.substr(0, slash), r, line), b = parse_rational(text.substr(slash + 1), r, line);
    if (b.is_zero()) r.fail(line, "division by zero in '" + text + "'");
    return a / b;
  }
  std::int64_t num = 0, den = 1;
  bool dot = false, any = false;
  int frac = 0;
  for (char c : text) {
    if (c == '.' && !dot) {
      dot = true;
    } else if (c >= '0' && c <= '9') {
      any = true;
      if (dot && ++frac > 9)
        r.fail(line, "coefficient '" + text + "' has more than 9 decimals: cgagen's basis change is exact; write "
                     "the null vectors with rational coefficients (ei = ep + em, eo = 0.5*em - 0.5*ep)");
      if (num > (INT64_MAX - 9) / 10) r.fail(line, "coefficient '" + text + "' is too large");
      num = num * 10 + (c - '0');
      if (dot) den *= 10;
    } else {
      r.fail(line, "bad number '" + text + "'");
    }
  }
  if (!any) r.fail(line, "bad number '" + text + "'");
  return Rational(num, den);
}

// "0.5*einf-e0" over the names `basis` -> index -> coefficient.
std::map<int, Rational> parse_combination(const std::string& text, const std::vector<std::string>& basis,
                                          const CsvReader& r, int line) {
  std::map<int, Rational> out;
  size_t i = 0;
  const std::string s = trim(text);
  if (s.empty()) r.fail(line, "empty right-hand side");
  while (i < s.size()) {
    int sign = 1;
    while (i < s.size() && (s[i] == '+' || s[i] == '-' || s[i] == ' ')) {
      if (s[i] == '-') sign = -sign;
      ++i;
    }
    size_t end = i;
    while (end < s.size() && s[end] != '+' && s[end] != '-') ++end;
    std::string term = trim(s.substr(i, end - i));
    if (term.empty()) r.fail(line, "missing term in '" + s + "'");
    Rational coeff(sign);
    std::string name = term;
    auto star = term.find('*');
    if (star != std::string::npos) {
      coeff = coeff * parse_rational(trim(term.substr(0, star)), r, line);
      name = trim(term.substr(star + 1));
    }
    auto it = std::find(basis.begin(), basis.end(), name);
    if (it == basis.end()) r.fail(line, "'" + name + "' is not a vector of the basis this line refers to");
    Rational& slot = out[static_cast<int>(it - basis.begin())];
    slot = slot + coeff;
    i = end;
  }
  for (auto it = out.begin(); it != out.end();) it = it->second.is_zero() ? out.erase(it) : std::next(it);
  return out;
}

std::vector<std::string> parse_basis(const std::string& text, const CsvReader& r, int line) {
  std::vector<std::string> names = split(text, ',');
  if (names.empty() || names[0] != "1") r.fail(line, "a basis line starts with 1 (the scalar), e.g. 1,e1,e2,e3");
  names.erase(names.begin());
  for (size_t k = 0; k < names.size(); ++k) {
    if (!is_identifier(names[k])) r.fail(line, "'" + names[k] + "' is not a name");
    if (std::find(names.begin(), names.begin() + static_cast<long>(k), names[k]) != names.begin() + static_cast<long>(k))
      r.fail(line, "basis vector '" + names[k] + "' is listed twice");
  }
  if (names.empty()) r.fail(line, "the basis has no vectors");
  if (names.size() > static_cast<size_t>(Algebra::kMaxVectors))
    r.fail(line, std::to_string(names.size()) + " basis vectors; cgagen takes at most " +
                     std::to_string(Algebra::kMaxVectors));
  return names;
}

// Line 2 or 5: "name=combination,..." giving each vector of `from` that is not also in `to` over `to`.
std::vector<std::map<int, Rational>> parse_change(const std::string& text, const std::vector<std::string>& from,
                                                  const std::vector<std::string>& to, const CsvReader& r,
                                                  int line, const char* what) {
  std::vector<std::optional<std::map<int, Rational>>> got(from.size());
  for (const std::string& item : split(text, ',')) {
    auto eq = item.find('=');
    if (eq == std::string::npos) r.fail(line, "expected name=combination, got '" + item + "'");
    std::string name = trim(item.substr(0, eq));
    auto it = std::find(from.begin(), from.end(), name);
    if (it == from.end()) r.fail(line, "'" + name + "' is not a " + what + " vector");
    auto& slot = got[static_cast<size_t>(it - from.begin())];
    if (slot) r.fail(line, "'" + name + "' is defined twice");
    slot = parse_combination(item.substr(eq + 1), to, r, line);
  }
  std::vector<std::map<int, Rational>> out;
  for (size_t k = 0; k < from.size(); ++k) {
    if (got[k]) {
      out.push_back(*got[k]);
      continue;
    }
    auto same = std::find(to.begin(), to.end(), from[k]);
    if (same == to.end()) r.fail(line, std::string(what) + " vector '" + from[k] + "' is not defined on this line");
    out.push_back({{static_cast<int>(same - to.begin()), Rational(1)}});
  }
  return out;
}

}  // namespace

AlgebraSpec parse_definition(const std::string& text, const std::string& file, const std::string& name) {
  CsvReader r{file};
  std::vector<std::string> lines;
  std::stringstream ss(text);
  std::string l;
  while (std::getline(ss, l)) lines.push_back(l);
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();
  if (lines.size() < 4 || lines.size() > 5)
    r.fail(static_cast<int>(lines.size()) + (lines.empty() ? 1 : 0),
           "a definition.csv has 5 lines (user basis; diagonal vectors in user terms; diagonal basis; metric; "
           "user vectors in diagonal terms), this file has " + std::to_string(lines.size()));
  lines.resize(5);
  AlgebraSpec spec;
  spec.name = name;
  try {
    spec.user = parse_basis(lines[0], r, 1);
    spec.diagonal = parse_basis(lines[2], r, 3);
    if (spec.diagonal.size() != spec.user.size())
      r.fail(3, "the diagonal basis has " + std::to_string(spec.diagonal.size()) + " vectors, the user basis (line 1) " +
                    std::to_string(spec.user.size()));
    spec.metric.assign(spec.diagonal.size(), 2);
    for (const std::string& item : split(lines[3], ',')) {
      auto eq = item.find('=');
      if (eq == std::string::npos) r.fail(4, "expected name=1, name=-1 or name=0, got '" + item + "'");
      std::string v = trim(item.substr(0, eq)), m = trim(item.substr(eq + 1));
      auto it = std::find(spec.diagonal.begin(), spec.diagonal.end(), v);
      if (it == spec.diagonal.end()) r.fail(4, "'" + v + "' is not a diagonal basis vector (line 3)");
      int& slot = spec.metric[static_cast<size_t>(it - spec.diagonal.begin())];
      if (slot != 2) r.fail(4, "metric of '" + v + "' given twice");
      if (m == "1" || m == "+1" || m == "1.0") slot = 1;
      else if (m == "-1" || m == "-1.0") slot = -1;
      else if (m == "0" || m == "0.0") slot = 0;
      else r.fail(4, "the metric of '" + v + "' is '" + m + "'; a diagonal basis takes 1, -1 or 0");
    }
    for (size_t k = 0; k < spec.metric.size(); ++k)
      if (spec.metric[k] == 2) r.fail(4, "no metric for diagonal vector '" + spec.diagonal[k] + "'");
    spec.diagonal_in_user = parse_change(lines[1], spec.diagonal, spec.user, r, 2, "diagonal");
    spec.user_in_diagonal = parse_change(lines[4], spec.user, spec.diagonal, r, 5, "user");
    // Lines 2 and 5 must be inverse: every user vector, taken to the diagonal basis and back, is itself.
    for (size_t k = 0; k < spec.user.size(); ++k) {
      std::map<int, Rational> back;
      for (const auto& [d, c] : spec.user_in_diagonal[k])
        for (const auto& [u, cu] : spec.diagonal_in_user[static_cast<size_t>(d)]) back[u] = back[u] + c * cu;
      for (auto it = back.begin(); it != back.end();) it = it->second.is_zero() ? back.erase(it) : std::next(it);
      if (back != std::map<int, Rational>{{static_cast<int>(k), Rational(1)}})
        r.fail(5, "user vector '" + spec.user[k] + "' taken to the diagonal basis (line 5) and back (line 2) is not "
                  "itself: the two basis changes are not inverse");
    }
  } catch (const std::overflow_error& e) {
    r.fail(5, std::string("coefficients too large for exact arithmetic: ") + e.what());
  }
  return spec;
}

// ---- the built-in algebras -------------------------------------------------------------------------------

namespace {

// Builds a spec from the user names, the diagonal names and metric, and pairs of null vectors: for each
// (o, i, p, m), user vectors o (origin-like) and i (infinity-like) over diagonal p (+1) and m (-1):
// i = m + p, o = (m - p)/2, so o.i = -1 and o^2 = i^2 = 0; back: p = i/2 - o, m = i/2 + o.
struct NullPair {
  std::string o, i, p, m;
};

AlgebraSpec make_spec(std::string name, std::vector<std::string> user, std::vector<std::string> diag,
                      std::vector<int> metric, const std::vector<NullPair>& pairs) {
  AlgebraSpec s;
  s.name = std::move(name);
  s.user = std::move(user);
  s.diagonal = std::move(diag);
  s.metric = std::move(metric);
  auto at = [](const std::vector<std::string>& v, const std::string& n) {
    auto it = std::find(v.begin(), v.end(), n);
    if (it == v.end()) throw std::logic_error("built-in algebra: no vector " + n);
    return static_cast<int>(it - v.begin());
  };
  s.user_in_diagonal.resize(s.user.size());
  s.diagonal_in_user.resize(s.diagonal.size());
  for (size_t k = 0; k < s.user.size(); ++k) {
    auto d = std::find(s.diagonal.begin(), s.diagonal.end(), s.user[k]);
    if (d != s.diagonal.end()) s.user_in_diagonal[k] = {{static_cast<int>(d - s.diagonal.begin()), Rational(1)}};
  }
  for (size_t k = 0; k < s.diagonal.size(); ++k) {
    auto u = std::find(s.user.begin(), s.user.end(), s.diagonal[k]);
    if (u != s.user.end()) s.diagonal_in_user[k] = {{static_cast<int>(u - s.user.begin()), Rational(1)}};
  }
  for (const NullPair& n : pairs) {
    const int o = at(s.user, n.o), i = at(s.user, n.i), p = at(s.diagonal, n.p), m = at(s.diagonal, n.m);
    s.user_in_diagonal[static_cast<size_t>(i)] = {{p, Rational(1)}, {m, Rational(1)}};
    s.user_in_diagonal[static_cast<size_t>(o)] = {{p, Rational(-1, 2)}, {m, Rational(1, 2)}};
    s.diagonal_in_user[static_cast<size_t>(p)] = {{i, Rational(1, 2)}, {o, Rational(-1)}};
    s.diagonal_in_user[static_cast<size_t>(m)] = {{i, Rational(1, 2)}, {o, Rational(1)}};
  }
  return s;
}

AlgebraSpec builtin_spec(const std::string& name) {
  if (name == "2d") return make_spec(name, {"e1", "e2"}, {"e1", "e2"}, {1, 1}, {});
  if (name == "3d") return make_spec(name, {"e1", "e2", "e3"}, {"e1", "e2", "e3"}, {1, 1, 1}, {});
  if (name == "2dpga") return make_spec(name, {"e0", "e1", "e2"}, {"e0", "e1", "e2"}, {0, 1, 1}, {});
  if (name == "3dpga") return make_spec(name, {"e0", "e1", "e2", "e3"}, {"e0", "e1", "e2", "e3"}, {0, 1, 1, 1}, {});
  // Space-time algebra: Hestenes' gamma_0..gamma_3, signature (+ - - -).
  if (name == "sta") return make_spec(name, {"e0", "e1", "e2", "e3"}, {"e0", "e1", "e2", "e3"}, {1, -1, -1, -1}, {});
  // Compass-ruler algebra: the conformal model of the plane.
  if (name == "cra")
    return make_spec(name, {"e1", "e2", "einf", "e0"}, {"e1", "e2", "ep", "em"}, {1, 1, 1, -1},
                     {{"e0", "einf", "ep", "em"}});
  if (name == "cga") {
    AlgebraSpec s = make_spec(name, {"e1", "e2", "e3", "einf", "e0"}, {"e1", "e2", "e3", "ep", "em"},
                              {1, 1, 1, 1, -1}, {{"e0", "einf", "ep", "em"}});
    s.cga_idents = true;
    return s;
  }
  // Conformal conics (Perwass; Hrdina, Navrat, Vasik): three null pairs (+, -, cross), R(5,3).
  if (name == "gac")
    return make_spec(name, {"e1", "e2", "e0p", "e0m", "e0c", "einfp", "einfm", "einfc"},
                     {"e1", "e2", "ep1", "ep2", "ep3", "em1", "em2", "em3"}, {1, 1, 1, 1, 1, -1, -1, -1},
                     {{"e0p", "einfp", "ep1", "em1"}, {"e0m", "einfm", "ep2", "em2"}, {"e0c", "einfc", "ep3", "em3"}});
  // Quadric GA (Zamora): one null pair per axis, R(6,3).
  if (name == "qga")
    return make_spec(name, {"e1", "e2", "e3", "eo1", "eo2", "eo3", "ei1", "ei2", "ei3"},
                     {"e1", "e2", "e3", "ep1", "ep2", "ep3", "em1", "em2", "em3"}, {1, 1, 1, 1, 1, 1, -1, -1, -1},
                     {{"eo1", "ei1", "ep1", "em1"}, {"eo2", "ei2", "ep2", "em2"}, {"eo3", "ei3", "ep3", "em3"}});
  // Double conformal GA (Easter, Hitzer): two copies of CGA, R(8,2).
  if (name == "dcga")
    return make_spec(name, {"e1", "e2", "e3", "eo1", "ei1", "e6", "e7", "e8", "eo2", "ei2"},
                     {"e1", "e2", "e3", "e4", "e5", "e6", "e7", "e8", "e9", "e10"}, {1, 1, 1, 1, -1, 1, 1, 1, 1, -1},
                     {{"eo1", "ei1", "e4", "e5"}, {"eo2", "ei2", "e9", "e10"}});
  // Cubic conformal GA of the plane: seven null pairs, R(9,7), 16 vectors.
  if (name == "ccga") {
    std::vector<std::string> user{"e1", "e2"}, diag{"e1", "e2"};
    std::vector<int> metric{1, 1};
    std::vector<NullPair> pairs;
    for (int k = 1; k <= 7; ++k) {
      user.push_back("eo" + std::to_string(k));
      user.push_back("ei" + std::to_string(k));
      pairs.push_back({"eo" + std::to_string(k), "ei" + std::to_string(k), "ep" + std::to_string(k), "em" + std::to_string(k)});
    }
    for (int k = 1; k <= 7; ++k) diag.push_back("ep" + std::to_string(k)), metric.push_back(1);
    for (int k = 1; k <= 7; ++k) diag.push_back("em" + std::to_string(k)), metric.push_back(-1);
    return make_spec(name, user, diag, metric, pairs);
  }
  throw std::logic_error("no built-in algebra " + name);
}

std::shared_ptr<const Algebra>& current_slot() {
  thread_local std::shared_ptr<const Algebra> a = builtin("cga");
  return a;
}

}  // namespace

const std::vector<std::string>& builtin_names() {
  static const std::vector<std::string> names = {"2d",  "3d",  "2dpga", "3dpga", "cra",  "sta",
                                                 "cga", "gac", "qga",   "dcga",  "ccga"};
  return names;
}

std::shared_ptr<const Algebra> builtin(const std::string& name) {
  static std::mutex lock;  // threads may each compile
  static std::map<std::string, std::shared_ptr<const Algebra>> made;
  if (std::find(builtin_names().begin(), builtin_names().end(), name) == builtin_names().end()) return nullptr;
  const std::lock_guard<std::mutex> hold(lock);
  auto& slot = made[name];
  if (!slot) slot = std::make_shared<const Algebra>(builtin_spec(name));
  return slot;
}

std::shared_ptr<const Algebra> load(const std::string& name_or_file) {
  if (auto a = builtin(name_or_file)) return a;
  std::ifstream in(name_or_file, std::ios::binary);
  if (!in) {
    std::string known;
    for (const auto& n : builtin_names()) known += (known.empty() ? "" : ", ") + n;
    throw AlgebraError("unknown algebra '" + name_or_file + "': neither a built-in (" + known +
                       ") nor a readable definition.csv file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  std::string stem = name_or_file;
  if (auto slash = stem.find_last_of("/\\"); slash != std::string::npos) stem = stem.substr(slash + 1);
  if (auto dot = stem.rfind('.'); dot != std::string::npos) stem = stem.substr(0, dot);
  return std::make_shared<const Algebra>(parse_definition(text.str(), name_or_file, stem));
}

const Algebra& current() { return *current_slot(); }
std::shared_ptr<const Algebra> current_shared() { return current_slot(); }
void use(std::shared_ptr<const Algebra> a) { current_slot() = std::move(a); }

Using::Using(std::shared_ptr<const Algebra> a) : previous_(current_slot()) {
  if (a) use(std::move(a));
}
Using::~Using() { use(previous_); }

}  // namespace cgagen::algebra
