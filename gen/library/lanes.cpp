// 4-wide forms of library kernels (lanes.hpp): the forms read off a kernel's expressions, and their statements
// over the helpers that templates/cpp/library/file.in defines (load, store, splat, perm, flip, scale in
// namespace x4).
#include "library/lanes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

namespace cgagen::library {

std::string float_literal(double c) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", c);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s + "f";
}

std::string vector_literal(const std::array<double, 4>& c) {
  std::string e = "v4{";
  for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + float_literal(c[l]);
  return e + "}";
}

namespace {

// A symbol's operand (0 a, 1 b) and coefficient index, or nothing for any other symbol.
using SymbolIndex = std::map<GiNaC::ex, std::pair<int, size_t>, GiNaC::ex_is_less>;

// A term's numeric coefficient and the coefficient indices of each operand it multiplies, a power counted as
// its exponent's many factors; false for a non-rational coefficient or a factor that is not an input's.
bool read_factors(const GiNaC::ex& term, const SymbolIndex& index, GiNaC::numeric& c, std::vector<size_t> (&seen)[2]) {
  c = 1;
  auto factor = [&](const GiNaC::ex& f) {
    if (GiNaC::is_a<GiNaC::numeric>(f)) {
      c *= GiNaC::ex_to<GiNaC::numeric>(f);
      return true;
    }
    GiNaC::ex base = f;
    long times = 1;
    if (GiNaC::is_a<GiNaC::power>(f)) {
      const GiNaC::ex e = f.op(1);
      if (!GiNaC::is_a<GiNaC::numeric>(e) || !GiNaC::ex_to<GiNaC::numeric>(e).is_pos_integer()) return false;
      times = GiNaC::ex_to<GiNaC::numeric>(e).to_long();
      if (times > 3) return false;
      base = f.op(0);
    }
    auto it = index.find(base);
    if (it == index.end()) return false;
    for (long k = 0; k < times; ++k) seen[it->second.first].push_back(it->second.second);
    return true;
  };
  if (GiNaC::is_a<GiNaC::mul>(term)) {
    for (size_t k = 0; k < term.nops(); ++k)
      if (!factor(term.op(k))) return false;
  } else if (!factor(term)) {
    return false;
  }
  return c.is_rational();
}

// Each output coefficient of a two-operand kernel as its expanded expression over the inputs (temporaries
// substituted), with the symbol index; nothing for another shape of kernel.
std::optional<std::pair<SymbolIndex, std::vector<GiNaC::ex>>> expanded(const opt::Program& program, size_t& na, size_t& nb) {
  if (program.inputs.size() != 2 || program.outputs.size() != 1) return std::nullopt;
  SymbolIndex index;
  for (int k = 0; k < 2; ++k) {
    const KernelInput& in = program.inputs[static_cast<size_t>(k)];
    for (size_t s = 0; s < in.symbols.size(); ++s) index[in.symbols[s]] = {k, s};
    (k == 0 ? na : nb) = in.symbols.size();
  }
  GiNaC::exmap temps;  // each temporary's value over the inputs alone
  for (const opt::Temp& t : program.temps) temps[t.sym] = t.value.subs(temps);
  std::vector<GiNaC::ex> out;
  for (const opt::OutputSlot& slot : program.outputs[0].slots) out.push_back(slot.value.subs(temps).expand());
  return std::make_pair(std::move(index), std::move(out));
}

// The terms of an expanded sum, each read by `read` into T; false where one is not of the form.
template <class T, class Read>
bool read_sum(const GiNaC::ex& e, std::vector<T>& terms, Read read) {
  if (e.is_zero()) return true;
  const bool sum = GiNaC::is_a<GiNaC::add>(e);
  for (size_t k = 0; k < (sum ? e.nops() : 1); ++k) {
    T t;
    if (!read(sum ? e.op(k) : e, t)) return false;
    terms.push_back(t);
  }
  return true;
}

auto width(size_t n, size_t g) { return std::min<size_t>(4, n - 4 * g); }

// The statements of one kernel: vectors made of lanes Σ c · x_i · y_j, with x_i broadcast and the y_j a
// shuffle of y's vectors. An i of kNone is a term without x (the shuffle alone), a j of kNone one without y
// (a constant, or x_i times a constant). Shuffles with the same lanes and coefficients are made once.
class Builder {
 public:
  Builder(std::string x, size_t nx, std::string y, size_t ny) : x_(std::move(x)), y_(std::move(y)) {
    widths_[x_] = nx;
    widths_[y_] = ny;
  }

  // A vector whose lane l is Σ over lanes[l] of t.c · x_{t.i} · y_{t.j}, as an expression (a balanced sum).
  // Each lane's terms are divided by the magnitude of its first coefficient, and the sum is scaled back by
  // one product at the end, so that ±2 (a sandwich's usual coefficient) costs a sign in a shuffle, not a
  // product per column. A lane without a term of y (0, or a constant) is scaled by 0 instead: the columns may
  // hold anything there, so a column that is a shuffle of y with signs in its other lanes needs no product.
  std::string vector(const std::array<std::vector<LaneTerm>, 4>& lanes, size_t used) {
    std::array<double, 4> kappa{1, 1, 1, 1};
    std::array<bool, 4> free{false, false, false, false};
    for (size_t l = 0; l < used; ++l) {
      free[l] = true;
      for (const LaneTerm& t : lanes[l])
        if (t.j != kNone) {
          kappa[l] = std::fabs(t.c);
          free[l] = false;
          break;
        }
      if (free[l]) kappa[l] = 0;
    }
    std::map<size_t, std::array<std::vector<LaneTerm>, 4>> by_x;  // i -> lane -> terms with y, over kappa
    std::array<double, 4> constant{};                              // the terms without y
    bool any_constant = false;
    for (size_t l = 0; l < used; ++l)
      for (const LaneTerm& t : lanes[l]) {
        if (t.j == kNone) {  // a constant: the forms put a lone factor in j
          constant[l] += t.c;
          any_constant = true;
        } else {
          by_x[t.i][l].push_back({t.i, t.j, t.c / kappa[l]});
        }
      }
    std::vector<std::string> columns;
    for (const auto& [i, per_lane] : by_x) {
      size_t depth = 0;
      for (const auto& terms : per_lane) depth = std::max(depth, terms.size());
      for (size_t d = 0; d < depth; ++d) {
        Operand op{std::vector<long>(4, -1), std::vector<double>(4, 0.0)};
        for (size_t l = 0; l < 4; ++l)
          if (free[l]) {
            op.first[l] = kFree;
          } else if (d < per_lane[l].size()) {
            op.first[l] = static_cast<long>(per_lane[l][d].j);
            op.second[l] = per_lane[l][d].c;
          }
        const std::string p = operand(op, used);
        columns.push_back(i == kNone ? p : splat(x_, i) + " * " + p);
        if (i != kNone) ++ops_;
      }
    }
    if (columns.empty()) return any_constant ? vector_literal(constant) : "v4{}";
    std::string s = sum(std::move(columns));
    if (std::any_of(kappa.begin(), kappa.end(), [](double k) { return k != 1.0; })) {
      s = "scale(" + s + ", " + vector_literal(kappa) + ")";
      ++ops_;
    }
    return any_constant ? sum({s, vector_literal(constant)}) : s;
  }

  // x or y's coefficient k broadcast to 4 lanes (counted once).
  std::string splat(const std::string& v, size_t k) {
    if (splats_.insert({v, k}).second) ++ops_;
    loads_[v].insert(k / 4);
    return "splat<" + std::to_string(k % 4) + ">(" + v + std::to_string(k / 4) + ")";
  }

  // A balanced sum of `terms` ("v4{}" where there are none), outer parentheses dropped.
  std::string sum(std::vector<std::string> terms) {
    if (terms.empty()) return "v4{}";
    while (terms.size() > 1) {
      std::vector<std::string> next;
      for (size_t k = 0; k + 1 < terms.size(); k += 2) next.push_back("(" + terms[k] + " + " + terms[k + 1] + ")");
      if (terms.size() % 2) next.push_back(terms.back());
      ops_ += terms.size() / 2;
      terms = std::move(next);
    }
    std::string s = terms[0];
    if (s.front() == '(' && s.back() == ')') {
      // Drop the outer pair only where it encloses the whole expression.
      int level = 0;
      bool whole = true;
      for (size_t k = 0; k + 1 < s.size() && whole; ++k) {
        level += s[k] == '(' ? 1 : s[k] == ')' ? -1 : 0;
        whole = level > 0;
      }
      if (whole) s = s.substr(1, s.size() - 2);
    }
    return s;
  }

  void statement(const std::string& s) { body_ += s; }
  void count(size_t ops) { ops_ += ops; }

  // The loads (of `order`'s variables, in that order), the negations, then the statements.
  LaneCode code(const std::vector<std::string>& order) const {
    LaneCode c;
    for (const std::string& v : order) {
      auto it = loads_.find(v);
      if (it == loads_.end()) {  // a normalized versor's sandwich of a pseudoscalar is ±b, whatever a is
        c.body += "  (void)" + v + ";\n";
        continue;
      }
      for (size_t g : it->second)
        c.body += "  const v4 " + v + std::to_string(g) + " = load<" + std::to_string(width(widths_.at(v), g)) + ">(" + v + " + " + std::to_string(4 * g) + ");\n";
    }
    for (size_t g : negated_) c.body += "  const v4 n" + y_ + std::to_string(g) + " = -" + y_ + std::to_string(g) + ";\n";
    c.body += body_;
    c.ops = ops_;
    return c;
  }

  void set_width(const std::string& v, size_t n) { widths_[v] = n; }

 private:
  // y's coefficients lane by lane (-1: the lane has no term, kFree: it may hold anything) times their
  // coefficients.
  using Operand = std::pair<std::vector<long>, std::vector<double>>;
  static constexpr long kFree = -2;

  // The named vector of an operand, made (and counted) the first time.
  std::string operand(const Operand& op, size_t lanes) {
    auto it = operands_.find(op);
    if (it != operands_.end()) return it->second;
    // The y vectors the lanes read: one or two go through a shuffle, more through a gather of scalars.
    std::set<long> src;
    for (long j : op.first)
      if (j >= 0) src.insert(j / 4);
    if (src.size() <= 2)
      for (long g : src) loads_[y_].insert(static_cast<size_t>(g));
    std::string e;
    const long first = *src.begin(), second = *src.rbegin();
    bool identity = src.size() == 1;
    for (size_t l = 0; l < 4 && identity; ++l) identity = op.first[l] < 0 || op.first[l] == first * 4 + static_cast<long>(l);
    bool unit = true, positive = true;
    for (size_t l = 0; l < 4; ++l) {
      unit = unit && (l >= lanes || op.first[l] == kFree || (op.first[l] >= 0 && std::fabs(op.second[l]) == 1.0));
      positive = positive && (op.first[l] < 0 || op.second[l] == 1.0);
    }
    // A two-vector shuffle: lane l takes index j % 4 of the first vector, or of the second (+4).
    auto shuffle = [&](auto from_second, const std::string& second_vector) {
      e = "perm<";
      for (size_t l = 0; l < 4; ++l) {
        const long j = op.first[l] == kFree ? first * 4 + static_cast<long>(l) : op.first[l] < 0 ? first * 4 : op.first[l];
        e += std::string(l ? ", " : "") + std::to_string(j % 4 + (from_second(l, j) ? 4 : 0));
      }
      e += ">(" + y_ + std::to_string(first) + ", " + second_vector + ")";
      ++ops_;
    };
    if (identity) {
      e = y_ + std::to_string(first);  // flipped below where some sign is -1
    } else if (src.size() == 1 && unit) {
      // The signs by the shuffle itself: each lane from y's vector or from its negation (one per vector).
      if (negated_.insert(static_cast<size_t>(first)).second) ++ops_;
      shuffle([&](size_t l, long) { return op.second[l] < 0; }, "n" + y_ + std::to_string(first));
      positive = true;
    } else if (src.size() <= 2) {
      shuffle([&](size_t, long j) { return j / 4 == second && second != first; }, y_ + std::to_string(second));
    } else {
      e = "v4{";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + (op.first[l] < 0 ? "0.0f" : y_ + "[" + std::to_string(op.first[l]) + "]");
      e += "}";
      ops_ += 3;
    }
    if (unit && !positive) {
      e = "flip(" + e + ", u4{";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + (op.second[l] < 0 ? "0x80000000u" : "0u");
      e += "})";
      ++ops_;
    } else if (!unit || !positive) {
      std::array<double, 4> c{};
      for (size_t l = 0; l < 4; ++l) c[l] = op.second[l];
      e = "scale(" + e + ", " + vector_literal(c) + ")";
      ++ops_;
    }
    // Lanes past the result's last coefficient are never stored: what they hold does not matter.
    const std::string name = "p" + std::to_string(operands_.size());
    body_ += "  const v4 " + name + " = " + e + ";\n";
    return operands_.emplace(op, name).first->second;
  }

  std::string x_, y_;
  std::map<std::string, size_t> widths_;
  std::map<std::string, std::set<size_t>> loads_;
  std::set<std::pair<std::string, size_t>> splats_;
  std::set<size_t> negated_;
  std::map<Operand, std::string> operands_;
  std::string body_;
  size_t ops_ = 0;
};

// The bilinear form's statements with the operand named `x` (a or b) broadcast and the other, `y`, shuffled;
// `form` has x's coefficients as its i and y's as its j.
LaneCode columns_code(const LaneForm& form, const std::string& x, const std::string& y) {
  Builder b(x, form.na, y, form.nb);
  for (size_t g = 0; g < (form.out.size() + 3) / 4; ++g) {
    const size_t lanes = width(form.out.size(), g);
    std::array<std::vector<LaneTerm>, 4> per_lane;
    for (size_t l = 0; l < lanes; ++l) per_lane[l] = form.out[4 * g + l];
    b.statement("  store<" + std::to_string(lanes) + ">(r + " + std::to_string(4 * g) + ", " + b.vector(per_lane, lanes) + ");\n");
  }
  return b.code({x, y});
}

}  // namespace

std::optional<LaneForm> lane_form(const opt::Program& program) {
  LaneForm form;
  const auto e = expanded(program, form.na, form.nb);
  if (!e) return std::nullopt;
  for (const GiNaC::ex& slot : e->second) {
    std::vector<LaneTerm> terms;
    const bool ok = read_sum(slot, terms, [&](const GiNaC::ex& term, LaneTerm& t) {
      GiNaC::numeric c;
      std::vector<size_t> seen[2];
      if (!read_factors(term, e->first, c, seen) || seen[0].size() != 1 || seen[1].size() != 1) return false;
      t = {seen[0][0], seen[1][0], c.to_double()};
      return true;
    });
    if (!ok) return std::nullopt;
    // GiNaC's order of a sum's terms is not the same from run to run; the printed code must be.
    std::sort(terms.begin(), terms.end(), [](const LaneTerm& p, const LaneTerm& q) { return std::tie(p.i, p.j) < std::tie(q.i, q.j); });
    form.out.push_back(std::move(terms));
  }
  return form;
}

LaneCode lane_code(const LaneForm& form) {
  LaneForm swapped{form.nb, form.na, {}};
  for (const auto& terms : form.out) {
    swapped.out.emplace_back();
    for (const LaneTerm& t : terms) swapped.out.back().push_back({t.j, t.i, t.c});
  }
  LaneCode first = columns_code(form, "a", "b");
  LaneCode second = columns_code(swapped, "b", "a");
  return second.ops < first.ops ? second : first;
}

std::optional<LinearForm> linear_form(const opt::Program& program) {
  LinearForm form;
  const auto e = expanded(program, form.na, form.nb);
  if (!e) return std::nullopt;
  for (const GiNaC::ex& slot : e->second) {
    std::vector<LinearTerm> terms;
    const bool ok = read_sum(slot, terms, [&](const GiNaC::ex& term, LinearTerm& t) {
      GiNaC::numeric c;
      std::vector<size_t> seen[2];
      if (!read_factors(term, e->first, c, seen) || seen[0].size() > 2 || seen[1].size() != 1) return false;
      std::sort(seen[0].begin(), seen[0].end());
      t.p = seen[0].size() > 0 ? seen[0][0] : kNone;
      t.q = seen[0].size() > 1 ? seen[0][1] : kNone;
      t.j = seen[1][0];
      t.c = c.to_double();
      return true;
    });
    if (!ok) return std::nullopt;
    std::sort(terms.begin(), terms.end(), [](const LinearTerm& u, const LinearTerm& v) { return std::tie(u.j, u.p, u.q) < std::tie(v.j, v.p, v.q); });
    form.out.push_back(std::move(terms));
  }
  return form;
}

namespace {

// The vectors m_gj of M(a) for each group g, made by `b` (identical ones once), with their names: per group,
// per j with a term. `low`: each a's product a_p a_q broadcasts a_p (the lower index of the two), else a_q.
std::vector<std::map<size_t, std::string>> matrix_columns(Builder& b, const LinearForm& form, bool low) {
  // Each vector made so far with its lanes' polynomials: b_j and b_k can meet the same polynomials (a
  // rotation's columns in a line's two halves).
  std::vector<std::pair<std::array<std::vector<LaneTerm>, 4>, std::string>> made;
  auto same = [](const std::array<std::vector<LaneTerm>, 4>& u, const std::array<std::vector<LaneTerm>, 4>& v) {
    for (size_t l = 0; l < 4; ++l) {
      if (u[l].size() != v[l].size()) return false;
      for (size_t m = 0; m < u[l].size(); ++m)
        if (u[l][m].i != v[l][m].i || u[l][m].j != v[l][m].j || u[l][m].c != v[l][m].c) return false;
    }
    return true;
  };
  std::vector<std::map<size_t, std::string>> groups;
  for (size_t g = 0; g < (form.out.size() + 3) / 4; ++g) {
    const size_t lanes = width(form.out.size(), g);
    std::map<size_t, std::array<std::vector<LaneTerm>, 4>> by_b;  // j -> lane -> the polynomial in a
    for (size_t l = 0; l < lanes; ++l)
      for (const LinearTerm& t : form.out[4 * g + l]) {
        LaneTerm u{t.p, t.q, t.c};  // x_i y_j with x = y = a; kNone where a factor is missing
        if (t.q == kNone) u = {kNone, t.p, t.c};
        else if (!low) u = {t.q, t.p, t.c};
        by_b[t.j][l].push_back(u);
      }
    groups.emplace_back();
    for (const auto& [j, per_lane] : by_b) {
      auto it = std::find_if(made.begin(), made.end(), [&](const auto& c) { return same(c.first, per_lane); });
      if (it == made.end()) {
        const std::string name = "m" + std::to_string(made.size());
        b.statement("  const v4 " + name + " = " + b.vector(per_lane, lanes) + ";\n");
        made.emplace_back(per_lane, name);
        it = made.end() - 1;
      }
      groups.back()[j] = it->second;
    }
  }
  return groups;
}

// The linear form's statements: r's group g is the sum of splat(b_j) * m_gj.
LaneCode linear_columns_code(const LinearForm& form, bool low) {
  Builder b("a", form.na, "a", form.na);
  b.set_width("b", form.nb);
  const auto groups = matrix_columns(b, form, low);
  for (size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::string> terms;
    for (const auto& [j, column] : groups[g]) {
      terms.push_back(b.splat("b", j) + " * " + column);
      b.count(1);
    }
    b.statement("  store<" + std::to_string(width(form.out.size(), g)) + ">(r + " + std::to_string(4 * g) + ", " + b.sum(terms) + ");\n");
  }
  return b.code({"a", "b"});
}

// M(a)'s statements: each column stored.
LaneCode matrix_columns_code(const LinearForm& form, bool low) {
  Builder b("a", form.na, "a", form.na);
  const auto groups = matrix_columns(b, form, low);
  for (size_t j = 0; j < form.nb; ++j)
    for (size_t g = 0; g < groups.size(); ++g) {
      const auto it = groups[g].find(j);
      b.statement("  store<" + std::to_string(width(form.out.size(), g)) + ">(c" + std::to_string(j) + " + " + std::to_string(4 * g) + ", " +
                  (it == groups[g].end() ? std::string("v4{}") : it->second) + ");\n");
    }
  return b.code({"a"});
}

}  // namespace

LaneCode linear_code(const LinearForm& form) {
  LaneCode low = linear_columns_code(form, true);
  LaneCode high = linear_columns_code(form, false);
  LaneCode best = high.ops < low.ops ? high : low;
  if (LaneCode diagonal = diagonal_code(form); diagonal.ops < best.ops) best = std::move(diagonal);
  return best;
}

LaneCode matrix_code(const LinearForm& form) {
  LaneCode low = matrix_columns_code(form, true);
  LaneCode high = matrix_columns_code(form, false);
  return high.ops < low.ops ? high : low;
}

}  // namespace cgagen::library
