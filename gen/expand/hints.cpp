// Hints in the expander's diagnostics (see hints.hpp): edit distance, candidate choice and the table of
// other libraries' names.
#include "expand/hints.hpp"

#include <algorithm>
#include <cctype>
#include <map>

namespace cgagen::hints {

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

namespace {
size_t length_gap(const std::string& a, const std::string& b) {
  return a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
}
}  // namespace

bool looks_like_typo(const std::string& name, const std::string& known, bool short_ok) {
  if (name == known || name.empty() || known.empty()) return false;
  if (name.size() < 3 || known.size() < 3) {
    // A short assigned name with a letter doubled (Tt for T, snn for sn); nx, p1 or x2 next to n, p or x
    // are the usual coordinates and indices, no typos.
    if (!short_ok || length_gap(name, known) != 1) return false;
    const std::string& longer = name.size() > known.size() ? name : known;
    const std::string& shorter = name.size() > known.size() ? known : name;
    auto same = [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b)); };
    for (size_t i = 0; i < longer.size(); ++i) {
      const bool doubled = (i > 0 && same(longer[i], longer[i - 1])) || (i + 1 < longer.size() && same(longer[i], longer[i + 1]));
      if (doubled && longer.substr(0, i) + longer.substr(i + 1) == shorter) return true;
    }
    return false;
  }
  const size_t allowed = std::min(name.size(), known.size()) >= 8 ? 2 : 1;
  return length_gap(name, known) <= allowed && edit_distance(name, known) <= allowed;
}

std::optional<std::string> closest(const std::string& name, const std::vector<std::string>& known, bool short_ok) {
  std::optional<std::string> best;
  std::pair<size_t, size_t> best_rank;
  for (const std::string& k : known)
    if (looks_like_typo(name, k, short_ok)) {
      const std::pair<size_t, size_t> rank{edit_distance(name, k), length_gap(name, k)};
      if (!best || rank < best_rank) best = k, best_rank = rank;
    }
  return best;
}

namespace {
// A name's stem and number (a10: a, 10), or none when it does not end in digits after a non-digit.
std::optional<std::pair<std::string, std::string>> numbered(const std::string& name) {
  size_t i = name.size();
  while (i > 0 && std::isdigit(static_cast<unsigned char>(name[i - 1]))) --i;
  if (i == 0 || i == name.size()) return std::nullopt;
  return std::pair{name.substr(0, i), name.substr(i)};
}

// Is `name` a member of a numbered family: a one-letter stem, or another name of its stem among `names`?
bool in_family(const std::string& name, const std::string& stem, const std::vector<std::string>& names) {
  if (stem.size() == 1) return true;
  for (const std::string& n : names)
    if (n != name)
      if (auto s = numbered(n); s && s->first == stem) return true;
  return false;
}
}  // namespace

std::optional<std::string> for_read(const std::string& name, const std::vector<std::string>& variables,
                                    const std::vector<std::string>& functions,
                                    const std::vector<std::string>& inputs) {
  std::vector<std::string> candidates = variables;
  if (auto own = numbered(name); own && (in_family(name, own->first, variables) || in_family(name, own->first, inputs))) {
    // A chain's joint angles a1 ... a10 next to its products C2 ... C10: a10 is no misspelt C10.
    std::erase_if(candidates, [&](const std::string& k) {
      auto other = numbered(k);
      return other && other->first != own->first;
    });
  }
  if (auto v = closest(name, candidates, true)) return v;
  return closest(name, functions);
}

std::string for_call(const std::string& name, const std::vector<std::string>& functions) {
  // Other libraries' names (ganja.js, clifford, galgebra, Gaalop's own, GATL, ...), lower-cased, and what
  // cgagen writes instead. A name that is also a cgagen function never gets here.
  static const std::map<std::string, std::string> other = {
      {"inverse", "; did you mean 'invert'?"},
      {"inv", "; did you mean 'invert'?"},
      {"reverse", "; cgagen writes the reverse as ~X"},
      {"rev", "; cgagen writes the reverse as ~X"},
      {"reversion", "; cgagen writes the reverse as ~X"},
      {"dual", "; cgagen writes the dual as *X (or Dual(X) in algebras that define it)"},
      {"norm", "; did you mean 'abs'? (abs(X) of a multivector is its magnitude)"},
      {"magnitude", "; did you mean 'abs'? (abs(X) of a multivector is its magnitude)"},
      {"length", "; did you mean 'abs'? (abs(X) of a multivector is its magnitude)"},
      {"normalized", "; did you mean 'normalize'?"},
      {"unit", "; did you mean 'normalize'?"},
      {"inner", "; cgagen writes Gaalop's (Hestenes') inner product as A . B or hip(A, B); see also dot, lcont, rcont"},
      {"lc", "; did you mean 'lcont'? (the left contraction)"},
      {"left_contraction", "; did you mean 'lcont'? (the left contraction)"},
      {"rc", "; did you mean 'rcont'? (the right contraction)"},
      {"right_contraction", "; did you mean 'rcont'? (the right contraction)"},
      {"sp", "; did you mean 'scp'? (the scalar product)"},
      {"scalar_product", "; did you mean 'scp'? (the scalar product)"},
      {"commutator", "; did you mean 'cp'? (the commutator product)"},
      {"inverse_geometric_product", "; did you mean 'igp'? (A * invert(B))"},
      {"normsq", "; did you mean 'rnorm_sqr'? (<X ~X>_0)"},
      {"norm2", "; did you mean 'rnorm_sqr'? (<X ~X>_0)"},
      {"squared_norm", "; did you mean 'rnorm_sqr'? (<X ~X>_0)"},
      {"wedge", "; cgagen writes the outer product as A ^ B"},
      {"outer", "; cgagen writes the outer product as A ^ B"},
      {"gp", "; cgagen writes the geometric product as A * B"},
      {"geometric", "; cgagen writes the geometric product as A * B"},
      {"join", "; cgagen has no 'join'; rp(A, B) is the regressive product, A ^ B the outer product"},
      {"meet", "; cgagen has no 'meet'; rp(A, B) is the regressive product"},
      {"regressive", "; did you mean 'rp'? (the regressive product)"},
      {"regressive_product", "; did you mean 'rp'? (the regressive product)"},
      {"vee", "; did you mean 'rp'? (the regressive product)"},
      {"grade_select", "; did you mean 'grade'? (grade(X, k))"},
      {"take_grade", "; did you mean 'grade'? (grade(X, k))"},
      {"involution", "; did you mean 'involute'? (the grade involution)"},
      {"grade_involution", "; did you mean 'involute'? (the grade involution)"},
      {"conjugation", "; did you mean 'conjugate'? (the Clifford conjugate)"},
      {"conj", "; did you mean 'conjugate'? (the Clifford conjugate)"},
      {"up", "; did you mean 'createPoint'? (the conformal point of x, y, z)"},
  };
  if (auto f = closest(name, functions)) return "; did you mean '" + *f + "'?";
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  auto it = other.find(lower);
  if (it != other.end()) {
    // A suggestion of a function this algebra lacks (Normalize, createPoint outside CGA) is no help.
    const auto q = it->second.find("did you mean '");
    if (q == std::string::npos) return it->second;
    const std::string fn = it->second.substr(q + 14, it->second.find('\'', q + 14) - q - 14);
    if (std::find(functions.begin(), functions.end(), fn) != functions.end()) return it->second;
  }
  return "";
}

namespace {
// The number an operand is as written ("2", "-0.5"), or "".
std::string number_text(const front::Expr& e) {
  if (e.kind == front::Expr::Kind::Number) return e.text;
  if (e.kind == front::Expr::Kind::Unary && e.unary_op == front::UnaryOp::Negate && !e.args.empty() &&
      e.args[0]->kind == front::Expr::Kind::Number)
    return "-" + e.args[0]->text;
  return "";
}
}  // namespace

std::optional<std::string> outer_with_number(const front::Expr& e) {
  if (e.kind != front::Expr::Kind::Binary || e.binary_op != front::BinaryOp::Outer || e.args.size() != 2)
    return std::nullopt;
  // Only a number on the right: Gaalop's scripts scale on the left on purpose (1 - 0.5^t^einf).
  const std::string n = number_text(*e.args[1]);
  if (n.empty()) return std::nullopt;
  const front::Expr& other = *e.args[0];
  const std::string x = other.kind == front::Expr::Kind::Name ? other.text : "X";
  return "'" + x + "^" + n + "' is the outer product with the number " + n + ", i.e. " + n + "*" + x +
         "; for a power write " + x + "*" + x + (n == "2" ? "" : "*...");
}

void warn_once(std::vector<front::Warning>& warnings, front::SourceLoc loc, const std::string& message) {
  for (const auto& w : warnings)
    if (w.loc.line == loc.line && w.loc.col == loc.col && w.message == message) return;
  warnings.push_back({loc, message});
}

}  // namespace cgagen::hints
