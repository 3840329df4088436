// The diagonal form of a kernel linear in b (lanes.hpp, diagonal_code): M(a)'s entries taken a diagonal at a
// time, each diagonal's lanes made together from products of two shuffles of a, as klein writes its
// sandwiches by hand. The form's choice of diagonals, the search for shuffles that its lanes share, and its
// statements over the helpers of templates/cpp/library/file.in (namespace x4).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "library/lanes.hpp"
#include "library/shuffles.hpp"

namespace cgagen::library {

namespace {

using namespace shuffles;

struct Term {
  long p = kAny, q = kAny;  // a_p a_q; q kAny for a_p alone, both for a constant
  double c = 0;
};

// One vector t to make, lane l the polynomial `lanes[l]` in a, and the shuffle of b it multiplies.
struct Target {
  std::array<std::vector<Term>, 4> lanes;
  Pattern b{kAny, kAny, kAny, kAny};
};

// The result coefficients a group's lanes compute (lane l row rows[l]; width = rows.size()), and its targets.
struct Group {
  std::vector<size_t> rows;
  size_t width = 0;
  std::vector<Target> targets;
};

// Where the result's coefficients are computed: per group vector, the rows of its lanes. The stored layout
// puts rows 4g .. 4g+3 in group g; another layout is shuffled into it before the stores.
using Layout = std::vector<std::vector<size_t>>;

// One product of two shuffles of a in a target's sum (v empty: a shuffle alone, a term of one factor), lane
// l the term picked there.
struct Pick {
  Pattern u{kAny, kAny, kAny, kAny}, v{kAny, kAny, kAny, kAny};
  std::array<double, 4> c{};      // per lane, the coefficient over kappa; NaN while not picked
  std::array<bool, 4> matters{};  // the lanes whose value counts
};

// How a pick's coefficients are paid for: 0 all +1 (a sum), 1 all -1 (a difference), 2 mixed ±1 (signs, in a
// shuffle or flipped), 3 another mix (a product with the coefficients).
int kind(const Pick& s, bool skip_zeros = false) {
  bool plus = true, minus = true, unit = true;
  for (size_t l = 0; l < 4; ++l) {
    if (!s.matters[l] || std::isnan(s.c[l]) || (skip_zeros && s.c[l] == 0.0)) continue;
    plus = plus && s.c[l] == 1.0;
    minus = minus && s.c[l] == -1.0;
    unit = unit && std::fabs(s.c[l]) == 1.0;
  }
  return plus ? 0 : minus ? 1 : unit ? 2 : 3;
}

Signs signs_of(const Pick& s) {
  Signs g = kPlus;
  for (size_t l = 0; l < 4; ++l)
    if (s.matters[l] && s.c[l] < 0) g[l] = -1;
  return g;
}

// p with kZero in the lanes where the pick's coefficient is 0.
Pattern zeroed(const Pattern& p, const Pick& s) {
  Pattern z = p;
  for (size_t l = 0; l < 4; ++l)
    if (s.matters[l] && s.c[l] == 0.0) z[l] = kZero;
  return z;
}

// What a complete pick costs, and where its coefficients go: 0 nowhere (a sum or a difference), 1 the signs
// on u, 2 on v, 3 a product after, 4 the zeros on u, 5 on v.
std::pair<long, int> pick_cost(const Pick& s, const Shuffles& sh) {
  const long plain = sh.cost(s.u) + sh.cost(s.v);
  const bool zeros = std::any_of(s.c.begin(), s.c.end(), [](double c) { return c == 0.0; });
  if (zeros) {
    // A lane without a term in this product: 0 from one factor's shuffle where the other lanes agree in sign.
    std::pair<long, int> best{plain + 1, 3};
    if (kind(s, true) <= 1) {
      const long on_u = sh.cost(zeroed(s.u, s)) + sh.cost(s.v);
      if (on_u <= best.first) best = {on_u, 4};
      if (!Shuffles::empty(s.v)) {
        const long on_v = sh.cost(s.u) + sh.cost(zeroed(s.v, s));
        if (on_v <= best.first) best = {on_v, 5};
      }
    }
    return best;
  }
  switch (kind(s)) {
    case 0:
    case 1: return {plain, 0};
    case 2: {
      const Signs g = signs_of(s);
      std::pair<long, int> best{plain + 1, 3};
      const long on_u = sh.cost(s.u, g) + sh.cost(s.v);
      if (on_u <= best.first) best = {on_u, 1};  // on a tie the signs: the negation is made once for all
      if (!Shuffles::empty(s.v)) {
        const long on_v = sh.cost(s.u) + sh.cost(s.v, g);
        if (on_v <= best.first) best = {on_v, 2};
      }
      return best;
    }
    default: return {plain + 1, 3};
  }
}

// A deterministic generator for the search's tie orders (the same sequence on every platform).
struct Rng {
  uint64_t s;
  uint64_t next() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return s;
  }
};

// A made term of a target's sum: its expression and whether it is subtracted.
struct Made {
  std::string e;
  bool minus = false;
};

// The products of one target: its terms of the same degree picked lane by lane so that each product's two
// shuffles are ones already made where possible, each lane divided by kappa[l] first; the shuffles are made
// in `sh` as they are picked. `rng` (if any) orders the candidates, so that restarts find other ways to share.
std::vector<Made> make_products(const Target& t, const std::array<double, 4>& kappa, const std::array<bool, 4>& live,
                                Shuffles& sh, std::string& body, size_t& ops, Rng* rng) {
  struct Choice {
    size_t term;
    bool swap;
  };
  std::array<std::vector<Term>, 4> left;
  for (size_t l = 0; l < 4; ++l)
    for (const Term& term : t.lanes[l])
      if (term.p != kAny) left[l].push_back({term.p, term.q, term.c / kappa[l]});
  std::vector<Made> made;
  for (int degree : {2, 1}) {
    for (;;) {
      std::array<std::vector<Choice>, 4> options;
      bool any = false;
      for (size_t l = 0; l < 4; ++l) {
        for (size_t k = 0; k < left[l].size(); ++k) {
          const Term& term = left[l][k];
          if ((term.q != kAny ? 2 : 1) != degree) continue;
          options[l].push_back({k, false});
          if (degree == 2 && term.p != term.q) options[l].push_back({k, true});
        }
        if (rng)
          for (size_t k = options[l].size(); k > 1; --k) std::swap(options[l][k - 1], options[l][rng->next() % k]);
        any = any || !options[l].empty();
      }
      if (!any) break;
      // Past kLeaves combinations the lanes with the most choices keep only their first ones.
      constexpr size_t kLeaves = 1 << 11;
      for (;;) {
        size_t leaves = 1, widest = 0;
        for (size_t l = 0; l < 4; ++l) {
          leaves *= std::max<size_t>(1, options[l].size());
          if (options[l].size() > options[widest].size()) widest = l;
        }
        if (leaves <= kLeaves) break;
        options[widest].resize(options[widest].size() / 2);
      }
      // Branch and bound over the lanes' choices; a live lane with no term of this degree left holds zero.
      Pick best, cur;
      long best_cost = 1 << 20;
      int best_where = 0;
      for (size_t l = 0; l < 4; ++l) {
        cur.matters[l] = live[l];
        cur.c[l] = std::nan("");
      }
      std::function<void(size_t)> walk = [&](size_t l) {
        if (best_cost == 0) return;
        if (sh.bound(cur.u) + sh.bound(cur.v) + (kind(cur) == 3 ? 1 : 0) >= best_cost) return;
        if (l == 4) {
          const auto [cost, where] = pick_cost(cur, sh);
          if (cost < best_cost) {
            best = cur;
            best_cost = cost;
            best_where = where;
          }
          return;
        }
        if (options[l].empty()) {
          if (live[l]) cur.c[l] = 0.0;
          walk(l + 1);
          cur.c[l] = std::nan("");
          return;
        }
        for (const Choice& ch : options[l]) {
          const Term& term = left[l][ch.term];
          cur.u[l] = ch.swap ? term.q : term.p;
          cur.v[l] = ch.swap ? term.p : term.q;
          cur.c[l] = term.c;
          walk(l + 1);
          cur.u[l] = cur.v[l] = kAny;
          cur.c[l] = std::nan("");
        }
      };
      walk(0);
      // Take the picked terms out.
      for (size_t l = 0; l < 4; ++l) {
        if (options[l].empty()) continue;
        for (size_t k = 0; k < left[l].size(); ++k) {
          const Term& term = left[l][k];
          const bool hit = term.c == best.c[l] &&
                           ((term.p == best.u[l] && term.q == best.v[l]) || (term.q == best.u[l] && term.p == best.v[l]));
          if (hit && (term.q != kAny ? 2 : 1) == degree) {
            left[l].erase(left[l].begin() + static_cast<long>(k));
            break;
          }
        }
      }
      const Signs g = signs_of(best);
      const std::string u = sh.make(best_where == 4 ? zeroed(best.u, best) : best.u, best_where == 1 ? g : kPlus, body, ops);
      const bool alone = Shuffles::empty(best.v);
      std::string e = u;
      if (!alone) {
        e += " * " + sh.make(best_where == 5 ? zeroed(best.v, best) : best.v, best_where == 2 ? g : kPlus, body, ops);
        ++ops;
      }
      const int k = kind(best, best_where >= 4);
      if (best_where == 3) {
        std::array<double, 4> c{};
        for (size_t l = 0; l < 4; ++l) c[l] = best.matters[l] ? best.c[l] : 0.0;
        e = "scale(" + e + ", " + vector_literal(c) + ")";
        ++ops;
      }
      made.push_back({e, k == 1});
    }
  }
  return made;
}

// The statements of one kernel, every target in order, and their operation count.
struct Built {
  std::string body;
  size_t ops = 0;       // vector operations, each shuffle one (as lanes.cpp counts them)
  long estimate = 0;    // x86 instructions, the shuffles at their price
};

// kappa: per lane the magnitude most of its terms have (the largest among equals), so that the slots'
// coefficients are mostly ±1; a lane that does not count is 0 where some other kappa is not 1 (the
// target's final product zeroes it).
std::array<double, 4> kappa_of(const Target& t, const std::array<bool, 4>& live) {
  std::array<double, 4> kappa{1, 1, 1, 1};
  for (size_t l = 0; l < 4; ++l) {
    std::map<double, int> count;
    for (const Term& term : t.lanes[l])
      if (term.p != kAny) ++count[std::fabs(term.c)];
    int most = 0;
    for (const auto& [mag, n] : count)
      if (n >= most) {
        most = n;
        kappa[l] = mag;
      }
    if (!live[l]) kappa[l] = 1;
  }
  return kappa;
}

// A target's lanes up to a sign per lane, as a key: two targets whose lanes are the same polynomials, or their
// negations, are made once (a motor turns a line's two halves by the same rotation). `sign` gets the lanes'
// signs against the key.
std::string target_key(const Target& t, size_t width, Signs& sign) {
  std::string key = std::to_string(width);
  for (size_t l = 0; l < 4; ++l) {
    std::vector<Term> terms = t.lanes[l];
    for (Term& term : terms)
      if (term.q != kAny && term.q < term.p) std::swap(term.p, term.q);
    std::sort(terms.begin(), terms.end(), [](const Term& x, const Term& y) { return std::tie(x.p, x.q, x.c) < std::tie(y.p, y.q, y.c); });
    sign[l] = terms.empty() || terms[0].c > 0 ? 1 : -1;
    key += "|";
    char buf[64];
    for (const Term& term : terms) {
      std::snprintf(buf, sizeof buf, "%ld,%ld,%.17g;", term.p, term.q, term.c * sign[l]);
      key += buf;
    }
  }
  return key;
}

bool stored_layout(const Layout& layout, size_t n) {
  if (layout.size() != (n + 3) / 4) return false;
  for (size_t g = 0; g < layout.size(); ++g)
    for (size_t l = 0; l < layout[g].size(); ++l)
      if (layout[g][l] != 4 * g + l) return false;
  return true;
}

Built build(const std::vector<Group>& groups, size_t na, size_t nb, size_t n_out, Rng* rng) {
  Built out;
  Shuffles sa("a", na), sb("b", nb);
  std::string body;
  std::map<std::string, std::pair<std::string, Signs>> made_targets;  // target_key -> its name and signs
  Layout layout;
  for (const Group& group : groups) layout.push_back(group.rows);
  const bool stored = stored_layout(layout, n_out);
  // A balanced sum ("" for none), each addition counted.
  auto sum = [&](std::vector<std::string> terms) {
    while (terms.size() > 1) {
      std::vector<std::string> next;
      for (size_t k = 0; k + 1 < terms.size(); k += 2) next.push_back("(" + terms[k] + " + " + terms[k + 1] + ")");
      if (terms.size() % 2) next.push_back(terms.back());
      out.ops += terms.size() / 2;
      terms = std::move(next);
    }
    return terms.empty() ? std::string() : terms[0];
  };
  for (size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    std::vector<std::string> products;
    for (const Target& t : group.targets) {
      Signs sign;
      const std::string key = target_key(t, group.width, sign);
      if (auto hit = made_targets.find(key); hit != made_targets.end()) {
        // The same lanes but for signs: the signs on b's shuffle where that costs no more than a flip of t.
        Signs g = kPlus;
        bool flipped = false;
        for (size_t l = 0; l < 4; ++l) {
          if (t.b[l] == kAny) continue;
          g[l] = sign[l] * hit->second.second[l];
          flipped = flipped || g[l] < 0;
        }
        std::string tv = hit->second.first, bv;
        if (flipped && sb.cost(t.b, g) > sb.cost(t.b) + 1) {
          tv = "flip(" + tv + ", u4{";
          for (size_t l = 0; l < 4; ++l) tv += std::string(l ? ", " : "") + (g[l] < 0 ? "0x80000000u" : "0u");
          tv += "})";
          ++out.ops;
          bv = sb.make(t.b, kPlus, body, out.ops);
        } else {
          bv = sb.make(t.b, g, body, out.ops);
        }
        products.push_back(tv + " * " + bv);
        ++out.ops;
        continue;
      }
      // Lanes that count for the products: stored ones with a term that has a factor of a. The other stored
      // lanes hold a constant or nothing, so the products must be zero there.
      std::array<bool, 4> live{};
      bool needs_zero = false;
      for (size_t l = 0; l < 4; ++l) {
        live[l] = l < group.width &&
                  std::any_of(t.lanes[l].begin(), t.lanes[l].end(), [](const Term& term) { return term.p != kAny; });
        needs_zero = needs_zero || (l < group.width && !live[l]);
      }
      std::array<double, 4> kappa = kappa_of(t, live);
      std::array<double, 4> constant{};
      bool any_constant = false;
      for (size_t l = 0; l < 4; ++l)
        for (const Term& term : t.lanes[l])
          if (term.p == kAny) {
            constant[l] += term.c;
            any_constant = true;
          }
      bool scaled = needs_zero;
      for (size_t l = 0; l < 4; ++l) scaled = scaled || (live[l] && kappa[l] != 1.0);
      // Where t is scaled anyway, a lane's kappa takes the sign of most of its terms (a restart's a random one),
      // so that more products have one sign in every lane.
      if (scaled)
        for (size_t l = 0; l < 4; ++l) {
          if (!live[l]) {
            kappa[l] = 0;
            continue;
          }
          double sign = 0;
          for (const Term& term : t.lanes[l])
            if (term.p != kAny && std::fabs(term.c) == kappa[l]) sign += term.c > 0 ? 1 : -1;
          if (rng ? rng->next() % 2 == 0 : sign < 0) kappa[l] = -kappa[l];
        }
      std::vector<std::string> plus, minus;
      for (const Made& m : make_products(t, kappa, live, sa, body, out.ops, rng)) (m.minus ? minus : plus).push_back(m.e);
      std::string value;
      if (!plus.empty() && !minus.empty()) {
        value = "(" + sum(plus) + " - " + sum(minus) + ")";
        ++out.ops;
      } else if (!plus.empty()) {
        value = sum(plus);
      } else if (!minus.empty()) {
        value = "(-" + sum(minus) + ")";
        ++out.ops;
      }
      if (!value.empty() && scaled) {
        value = "scale(" + value + ", " + vector_literal(kappa) + ")";
        ++out.ops;
      }
      if (any_constant) {
        if (!value.empty()) ++out.ops;
        value = value.empty() ? vector_literal(constant) : "(" + value + " + " + vector_literal(constant) + ")";
      }
      if (value.empty()) continue;
      const std::string name = "t" + std::to_string(g) + "_" + std::to_string(products.size());
      body += "  const v4 " + name + " = " + value + ";\n";
      made_targets.emplace(key, std::make_pair(name, sign));
      products.push_back(name + " * " + sb.make(t.b, kPlus, body, out.ops));
      ++out.ops;
    }
    std::string r = sum(products);
    if (r.empty()) r = "v4{}";
    if (r.front() == '(' && r.back() == ')' && products.size() > 1) r = r.substr(1, r.size() - 2);
    if (stored)
      body += "  store<" + std::to_string(group.width) + ">(r + " + std::to_string(4 * g) + ", " + r + ");\n";
    else
      body += "  const v4 g" + std::to_string(g) + " = " + r + ";\n";
  }
  // Another layout: each stored vector shuffled from the groups' (at most two of them, as `layouts` makes).
  Shuffles sg("g", 4 * groups.size());
  if (!stored) {
    std::vector<std::pair<size_t, size_t>> where(n_out);  // row -> (group, lane)
    for (size_t g = 0; g < layout.size(); ++g)
      for (size_t l = 0; l < layout[g].size(); ++l) where[layout[g][l]] = {g, l};
    for (size_t c = 0; 4 * c < n_out; ++c) {
      const size_t width = std::min<size_t>(4, n_out - 4 * c);
      Pattern p{kAny, kAny, kAny, kAny};
      for (size_t l = 0; l < width; ++l) p[l] = static_cast<long>(4 * where[4 * c + l].first + where[4 * c + l].second);
      body += "  store<" + std::to_string(width) + ">(r + " + std::to_string(4 * c) + ", " + sg.make(p, kPlus, body, out.ops) + ");\n";
    }
  }
  out.body = sa.loads() + sb.loads() + body;
  out.estimate = static_cast<long>(out.ops) + sa.extra() + sb.extra() + sg.extra();
  return out;
}

// The targets of each group of four result coefficients: first a column (a broadcast of b_j) for each j that
// the group reads as `columns` says, then the diagonals of the other j it reads, lane l of diagonal o taking
// the (l + o)-th of them cyclically.
// The column choices the search tries: the j that every lane reads, the j that one lane reads, both, none.
enum class Columns { kFull, kSingle, kBoth, kNone };

// `blocks` (if any) splits b's coefficients into blocks, and a diagonal then stays within one block: lane l
// of diagonal o of a block takes its (l + o)-th coefficient that the group reads.
std::vector<Group> targets(const LinearForm& form, Columns columns, const Layout& layout,
                           const std::vector<std::vector<size_t>>* blocks) {
  std::vector<Group> groups;
  for (const std::vector<size_t>& rows : layout) {
    Group group;
    group.rows = rows;
    group.width = rows.size();
    std::map<size_t, std::array<std::vector<Term>, 4>> entries;  // j -> lane -> terms
    for (size_t l = 0; l < group.width; ++l)
      for (const LinearTerm& t : form.out[rows[l]]) {
        Term term;
        if (t.p != kNone) term.p = static_cast<long>(t.p);
        if (t.q != kNone) term.q = static_cast<long>(t.q);
        if (term.p == kAny && term.q != kAny) std::swap(term.p, term.q);
        term.c = t.c;
        entries[t.j][l].push_back(term);
      }
    std::vector<size_t> rest;
    for (const auto& [j, lanes] : entries) {
      size_t readers = 0;
      for (size_t l = 0; l < group.width; ++l) readers += lanes[l].empty() ? 0 : 1;
      const bool full = readers == group.width, single = readers == 1 && group.width > 1;
      const bool column = (full && (columns == Columns::kFull || columns == Columns::kBoth)) ||
                          (single && (columns == Columns::kSingle || columns == Columns::kBoth));
      if (column) {
        Target t;
        t.lanes = lanes;
        t.b = {static_cast<long>(j), static_cast<long>(j), static_cast<long>(j), static_cast<long>(j)};
        group.targets.push_back(t);
      } else {
        rest.push_back(j);
      }
    }
    std::vector<std::vector<size_t>> runs{rest};  // the coefficients each run of diagonals cycles through
    if (blocks) {
      runs.clear();
      for (const std::vector<size_t>& block : *blocks) {
        std::vector<size_t> run;
        for (size_t j : block)
          if (std::find(rest.begin(), rest.end(), j) != rest.end()) run.push_back(j);
        if (!run.empty()) runs.push_back(std::move(run));
      }
    }
    for (const std::vector<size_t>& run : runs)
      for (size_t o = 0; o < run.size(); ++o) {
        Target t;
        bool any = false;
        for (size_t l = 0; l < group.width; ++l) {
          const size_t j = run[(l + o) % run.size()];
          const auto& lanes = entries.at(j);
          if (lanes[l].empty()) continue;
          t.lanes[l] = lanes[l];
          t.b[l] = static_cast<long>(j);
          any = true;
        }
        if (any) group.targets.push_back(t);
      }
    groups.push_back(std::move(group));
  }
  return groups;
}

// Where the rows go and how diagonals run: the stored layout with diagonals through all of b, and where they
// differ, the rows grouped by the coefficients of b they read and diagonals within blocks of b's coefficients
// read by the same row classes. A motor on a line: the Euclidean half reads the Euclidean half of b, the ideal
// half all of b; so grouped, both halves turn by the same rotation, whose diagonals are made once.
struct Arrangement {
  Layout layout;
  std::vector<std::vector<size_t>> blocks;  // empty: diagonals through all of b
};

std::vector<Arrangement> arrangements(const LinearForm& form) {
  const size_t n = form.out.size();
  Layout stored;
  for (size_t g = 0; 4 * g < n; ++g) {
    stored.emplace_back();
    for (size_t l = 4 * g; l < std::min(n, 4 * g + 4); ++l) stored.back().push_back(l);
  }
  // The row classes: rows that read the same coefficients of b, in the order of their first rows.
  std::vector<std::vector<size_t>> supports(n);
  for (size_t i = 0; i < n; ++i) {
    for (const LinearTerm& t : form.out[i]) supports[i].push_back(t.j);
    std::sort(supports[i].begin(), supports[i].end());
    supports[i].erase(std::unique(supports[i].begin(), supports[i].end()), supports[i].end());
  }
  std::vector<std::vector<size_t>> classes;  // rows
  for (size_t i = 0; i < n; ++i) {
    size_t c = 0;
    while (c < classes.size() && supports[classes[c][0]] != supports[i]) ++c;
    if (c == classes.size()) classes.emplace_back();
    classes[c].push_back(i);
  }
  // b's blocks: its coefficients read by the same classes.
  std::map<std::vector<size_t>, std::vector<size_t>> by_readers;
  std::vector<std::vector<size_t>> order;
  for (size_t j = 0; j < form.nb; ++j) {
    std::vector<size_t> readers;
    for (size_t c = 0; c < classes.size(); ++c)
      if (std::binary_search(supports[classes[c][0]].begin(), supports[classes[c][0]].end(), j)) readers.push_back(c);
    if (readers.empty()) continue;
    if (!by_readers.count(readers)) order.push_back(readers);
    by_readers[readers].push_back(j);
  }
  std::vector<std::vector<size_t>> blocks;
  for (const auto& readers : order) blocks.push_back(by_readers[readers]);
  if (blocks.size() < 2) blocks.clear();

  std::vector<Arrangement> out{{stored, {}}};
  if (!blocks.empty()) out.push_back({stored, blocks});
  Layout grouped;
  for (const std::vector<size_t>& rows : classes)
    for (size_t k = 0; k < rows.size(); k += 4) grouped.emplace_back(rows.begin() + static_cast<long>(k), rows.begin() + static_cast<long>(std::min(rows.size(), k + 4)));
  if (grouped == stored) return out;
  // Each stored vector is then one shuffle of at most two groups.
  for (size_t c = 0; 4 * c < n; ++c) {
    std::vector<size_t> from;
    for (size_t g = 0; g < grouped.size(); ++g)
      for (size_t i : grouped[g])
        if (i / 4 == c && std::find(from.begin(), from.end(), g) == from.end()) from.push_back(g);
    if (from.size() > 2) return out;
  }
  out.push_back({grouped, {}});
  if (!blocks.empty()) out.push_back({grouped, blocks});
  return out;
}

}  // namespace

LaneCode diagonal_code(const LinearForm& form) {
  // Restarts: searches with other tie orders, the first taking each first best choice. More find more
  // sharing (a motor on a line, 150 terms: 118 operations after 16, 113 after 64) but cost time (the 121
  // kernels of cga3.gal: 3.6 s after 16, 21 s after 64); the largest kernels get half.
  size_t terms = 0;
  for (const auto& out : form.out) terms += out.size();
  const int restarts = terms > 1000 ? 8 : 16;
  LaneCode best;
  long best_estimate = -1;
  for (const Arrangement& arrangement : arrangements(form))
    for (Columns columns : {Columns::kFull, Columns::kSingle, Columns::kBoth, Columns::kNone}) {
      const std::vector<Group> groups =
          targets(form, columns, arrangement.layout, arrangement.blocks.empty() ? nullptr : &arrangement.blocks);
      for (int k = 0; k < restarts; ++k) {
        Rng rng{0x9e3779b97f4a7c15ull + static_cast<uint64_t>(k)};
        const Built b = build(groups, form.na, form.nb, form.out.size(), k == 0 ? nullptr : &rng);
        if (best_estimate < 0 || b.estimate < best_estimate) {
          best = LaneCode{b.body, b.ops};
          best_estimate = b.estimate;
        }
      }
    }
  return best;
}

}  // namespace cgagen::library
