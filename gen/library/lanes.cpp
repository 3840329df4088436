// 4-wide forms of bilinear library kernels (lanes.hpp): the form read off a kernel's expressions, and its
// statements over the helpers that templates/cpp/library/file.in defines (load, store, splat, perm, flip,
// scale in namespace x4).
#include "library/lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

namespace cgagen::library {

namespace {

// A symbol's operand (0 a, 1 b) and coefficient index, or nothing for any other symbol.
using SymbolIndex = std::map<GiNaC::ex, std::pair<int, size_t>, GiNaC::ex_is_less>;

// One product term c * a_i * b_j, or false where `term` is anything else.
bool read_term(const GiNaC::ex& term, const SymbolIndex& index, LaneTerm& t) {
  GiNaC::numeric c = 1;
  int seen[2] = {-1, -1};
  auto factor = [&](const GiNaC::ex& f) {
    if (GiNaC::is_a<GiNaC::numeric>(f)) {
      c *= GiNaC::ex_to<GiNaC::numeric>(f);
      return true;
    }
    auto it = index.find(f);
    if (it == index.end() || seen[it->second.first] >= 0) return false;
    seen[it->second.first] = static_cast<int>(it->second.second);
    return true;
  };
  if (GiNaC::is_a<GiNaC::mul>(term)) {
    for (size_t k = 0; k < term.nops(); ++k)
      if (!factor(term.op(k))) return false;
  } else if (!factor(term)) {
    return false;
  }
  if (seen[0] < 0 || seen[1] < 0 || !c.is_rational()) return false;
  t = {static_cast<size_t>(seen[0]), static_cast<size_t>(seen[1]), c.to_double()};
  return true;
}

std::string number(double c) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", c);
  std::string s = buf;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s + "f";
}

}  // namespace

std::optional<LaneForm> lane_form(const opt::Program& program) {
  if (program.inputs.size() != 2 || program.outputs.size() != 1) return std::nullopt;
  SymbolIndex index;
  LaneForm form;
  for (int k = 0; k < 2; ++k) {
    const KernelInput& in = program.inputs[static_cast<size_t>(k)];
    for (size_t s = 0; s < in.symbols.size(); ++s) index[in.symbols[s]] = {k, s};
    (k == 0 ? form.na : form.nb) = in.symbols.size();
  }
  GiNaC::exmap temps;  // each temporary's value over the inputs alone
  for (const opt::Temp& t : program.temps) temps[t.sym] = t.value.subs(temps);
  for (const opt::OutputSlot& slot : program.outputs[0].slots) {
    const GiNaC::ex e = slot.value.subs(temps).expand();
    std::vector<LaneTerm> terms;
    if (!e.is_zero()) {
      const bool sum = GiNaC::is_a<GiNaC::add>(e);
      for (size_t k = 0; k < (sum ? e.nops() : 1); ++k) {
        LaneTerm t;
        if (!read_term(sum ? e.op(k) : e, index, t)) return std::nullopt;
        terms.push_back(t);
      }
    }
    // GiNaC's order of a sum's terms is not the same from run to run; the printed code must be.
    std::sort(terms.begin(), terms.end(), [](const LaneTerm& p, const LaneTerm& q) { return std::tie(p.i, p.j) < std::tie(q.i, q.j); });
    form.out.push_back(std::move(terms));
  }
  return form;
}

namespace {

// The columns with the operand named `x` (a or b) broadcast and the other, `y`, shuffled; `form` has x's
// coefficients as its i and y's as its j.
LaneCode columns_code(const LaneForm& form, const std::string& x, const std::string& y) {
  LaneCode code;
  std::string s;  // the statements after the loads
  auto groups = [](size_t n) { return (n + 3) / 4; };
  auto width = [](size_t n, size_t g) { return std::min<size_t>(4, n - 4 * g); };
  std::set<size_t> splats;           // the x_i broadcast
  std::set<long> y_groups;           // the vectors of y read
  std::set<long> negated;            // the vectors of y read negated
  // A column's operand: y's coefficients lane by lane (none: the lane has no term) times their coefficients.
  using Operand = std::pair<std::vector<long>, std::vector<double>>;
  std::map<Operand, std::string> operands;
  for (size_t g = 0; g < groups(form.out.size()); ++g) {
    const size_t lanes = width(form.out.size(), g);
    // Columns: for each x_i the group reads, the t-th term with x_i in every lane (one, on blade bases).
    std::map<size_t, std::vector<std::vector<const LaneTerm*>>> by_a;  // i -> lane -> terms
    for (size_t l = 0; l < lanes; ++l)
      for (const LaneTerm& t : form.out[4 * g + l]) {
        auto& per_lane = by_a[t.i];
        per_lane.resize(4);
        per_lane[l].push_back(&t);
      }
    std::vector<std::string> columns;
    for (const auto& [i, per_lane] : by_a) {
      size_t depth = 0;
      for (const auto& terms : per_lane) depth = std::max(depth, terms.size());
      for (size_t d = 0; d < depth; ++d) {
        Operand op{std::vector<long>(4, -1), std::vector<double>(4, 0.0)};
        for (size_t l = 0; l < 4; ++l)
          if (d < per_lane[l].size()) {
            op.first[l] = static_cast<long>(per_lane[l][d]->j);
            op.second[l] = per_lane[l][d]->c;
          }
        auto it = operands.find(op);
        if (it == operands.end()) {
          // The y vectors the lanes read: one or two go through a shuffle, more through a gather of scalars.
          std::set<long> src;
          for (long j : op.first)
            if (j >= 0) src.insert(j / 4);
          if (src.size() <= 2) y_groups.insert(src.begin(), src.end());
          std::string e;
          const long first = *src.begin(), second = *src.rbegin();
          bool identity = src.size() == 1;
          for (size_t l = 0; l < 4 && identity; ++l) identity = op.first[l] < 0 || op.first[l] == first * 4 + static_cast<long>(l);
          bool unit = true, positive = true;
          for (size_t l = 0; l < 4; ++l) {
            unit = unit && (l >= lanes || (op.first[l] >= 0 && std::fabs(op.second[l]) == 1.0));
            positive = positive && (op.first[l] < 0 || op.second[l] == 1.0);
          }
          // A two-vector shuffle: lane l takes index j % 4 of the first vector, or of the second (+4).
          auto shuffle = [&](auto from_second, const std::string& second_vector) {
            e = "perm<";
            for (size_t l = 0; l < 4; ++l) {
              const long j = op.first[l] < 0 ? first * 4 : op.first[l];
              e += std::string(l ? ", " : "") + std::to_string(j % 4 + (from_second(l, j) ? 4 : 0));
            }
            e += ">(" + y + std::to_string(first) + ", " + second_vector + ")";
            ++code.ops;
          };
          if (identity) {
            e = y + std::to_string(first);  // flipped below where some sign is -1
          } else if (src.size() == 1 && unit) {
            // The signs by the shuffle itself: each lane from y's vector or from its negation (one per vector).
            if (negated.insert(first).second) ++code.ops;
            shuffle([&](size_t l, long) { return op.second[l] < 0; }, "n" + y + std::to_string(first));
            positive = true;
          } else if (src.size() <= 2) {
            shuffle([&](size_t, long j) { return j / 4 == second && second != first; }, y + std::to_string(second));
          } else {
            e = "v4{";
            for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + (op.first[l] < 0 ? "0.0f" : y + "[" + std::to_string(op.first[l]) + "]");
            e += "}";
            code.ops += 3;
          }
          if (unit && !positive) {
            e = "flip(" + e + ", u4{";
            for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + (op.second[l] < 0 ? "0x80000000u" : "0u");
            e += "})";
            ++code.ops;
          } else if (!unit || !positive) {
            e = "scale(" + e + ", v4{";
            for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + number(op.second[l]);
            e += "})";
            ++code.ops;
          }
          // Lanes past the result's last coefficient are never stored: what they hold does not matter.
          const std::string name = "p" + std::to_string(operands.size());
          s += "  const v4 " + name + " = " + e + ";\n";
          it = operands.emplace(op, name).first;
        }
        if (splats.insert(i).second) ++code.ops;
        columns.push_back("splat<" + std::to_string(i % 4) + ">(" + x + std::to_string(i / 4) + ") * " + it->second);
        ++code.ops;
      }
    }
    std::string sum;
    if (columns.empty()) {
      sum = "v4{}";
    } else {
      while (columns.size() > 1) {
        std::vector<std::string> next;
        for (size_t k = 0; k + 1 < columns.size(); k += 2) next.push_back("(" + columns[k] + " + " + columns[k + 1] + ")");
        if (columns.size() % 2) next.push_back(columns.back());
        code.ops += columns.size() / 2;
        columns = std::move(next);
      }
      sum = columns[0];
      if (sum.front() == '(') sum = sum.substr(1, sum.size() - 2);
    }
    s += "  store<" + std::to_string(lanes) + ">(r + " + std::to_string(4 * g) + ", " + sum + ");\n";
  }
  std::set<size_t> a_groups;
  for (size_t i : splats) a_groups.insert(i / 4);
  for (size_t g : a_groups)
    code.body += "  const v4 " + x + std::to_string(g) + " = load<" + std::to_string(width(form.na, g)) + ">(" + x + " + " + std::to_string(4 * g) + ");\n";
  for (long g : y_groups)
    code.body += "  const v4 " + y + std::to_string(g) + " = load<" + std::to_string(width(form.nb, static_cast<size_t>(g))) + ">(" + y + " + " + std::to_string(4 * g) + ");\n";
  for (long g : negated) code.body += "  const v4 n" + y + std::to_string(g) + " = -" + y + std::to_string(g) + ";\n";
  code.body += s;
  return code;
}

}  // namespace

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

}  // namespace cgagen::library
