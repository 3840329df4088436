// Shuffles of one operand's 4-float vectors for the diagonal form (diagonals.cpp): the patterns a kernel
// asks for, with signs and zeros per lane, what a new one costs in x86 instructions, and its statement over
// the helpers of templates/cpp/library/file.in (namespace x4). Internal to the library stage.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cgagen::library::shuffles {

constexpr long kAny = -1;             // a lane whose value does not matter
constexpr long kZero = -2;            // a lane that holds 0
using Pattern = std::array<long, 4>;  // per lane, the operand's coefficient index (or kAny, kZero)

using Signs = std::array<int, 4>;  // per lane +1 or -1
constexpr Signs kPlus{1, 1, 1, 1};

// The shuffles of one operand (a or b) made so far, each with a sign per lane, and what a new one costs.
class Shuffles {
 public:
  Shuffles(std::string name, size_t n) : name_(std::move(name)), n_(n) {}

  // The operand's vector whose lanes these are, where p reads one vector in its own lane order (no
  // operation), or -1.
  long identity(const Pattern& p) const {
    long g = -1;
    for (size_t l = 0; l < 4; ++l) {
      if (p[l] == kAny) continue;
      if (p[l] == kZero) return -1;
      if (p[l] % 4 != static_cast<long>(l) || (g >= 0 && p[l] / 4 != g)) return -1;
      g = p[l] / 4;
    }
    return g;
  }

  // The made shuffle that p with signs s matches (the lanes that matter agree), or -1; `signed_` false
  // matches any signs.
  long find(const Pattern& p, const Signs& s, bool signed_ = true) const {
    for (size_t k = 0; k < made_.size(); ++k) {
      bool ok = true;
      for (size_t l = 0; l < 4 && ok; ++l) ok = p[l] == kAny || (p[l] == made_[k].first[l] && (!signed_ || s[l] == made_[k].second[l]));
      if (ok) return static_cast<long>(k);
    }
    return -1;
  }

  // A lower bound of what p costs whatever its signs.
  long bound(const Pattern& p) const {
    if (empty(p) || identity(p) >= 0 || find(p, kPlus, false) >= 0) return 0;
    return 1;
  }

  // What p with signs s costs now, in x86 instructions: 0 for one already made or a vector as loaded, else
  // its price.
  long cost(const Pattern& p, const Signs& s = kPlus) const {
    if (empty(p)) return 0;
    bool plus = true;
    for (size_t l = 0; l < 4; ++l) plus = plus && (p[l] == kAny || s[l] == 1);
    if (plus && identity(p) >= 0) return 0;
    if (find(p, s) >= 0) return 0;
    return price(p, s, plus);
  }

  // The instructions a new shuffle takes on x86 (AVX2 or AVX-512), the measure the search minimizes: a
  // shuffle of one vector or a broadcast 1 (vpermilps); of two vectors 1 where each half of the lanes reads
  // one (vshufps), else 2 (an index load and vpermi2ps, or two shuffles); zeros 1 more (a blend with zero)
  // unless the other lanes are in place; a gather from more vectors 4; signs by a shuffle from the vector
  // and its negation (the negation made once) or 1 more (an xor).
  long price(const Pattern& p, const Signs& s, bool plus) const {
    const Sources src = sources(p);
    const bool zeros = std::find(p.begin(), p.end(), kZero) != p.end();
    if (src.size() > 2) return 4 + (plus ? 0 : 1);
    if (plus) {
      if (zeros) {
        Pattern rest = p;
        for (long& i : rest)
          if (i == kZero) i = kAny;
        return identity(rest) >= 0 ? 1 : price(rest, kPlus, true) + 1;
      }
      return src.size() == 1 || halves(p, [](size_t, long i) { return i / 4; }) || insertion(p).lane >= 0 ? 1 : 2;
    }
    if (src.size() == 1 && !zeros) {
      const long negation = negated_.count(src.lo) ? 0 : 1;
      return negation + (halves(p, [&](size_t l, long) { return static_cast<long>(s[l]); }) ? 1 : 2);
    }
    return cost(p) + 1;
  }

  // The name of p with signs s, made (its statement appended to `body`, `ops` counting it) if new.
  std::string make(const Pattern& p, const Signs& s, std::string& body, size_t& ops) {
    bool plus = true;
    for (size_t l = 0; l < 4; ++l) plus = plus && (p[l] == kAny || s[l] == 1);
    const long g = identity(p);
    if (plus && g >= 0) return use(g);
    const long k = find(p, s);
    if (k >= 0) return names_[static_cast<size_t>(k)];
    // The estimate counts the outermost shuffle's price, whatever shuffles it makes first.
    const bool top = depth_++ == 0;
    const size_t ops_before = ops;
    const long priced = price(p, s, plus);
    // The lanes that do not matter: a broadcast stays one, else the lane's own index where that keeps one
    // source vector, else the first index that matters. They take sign +.
    Pattern full = p;
    Signs signs = s;
    const Sources src = sources(p);
    const bool zeros = std::find(p.begin(), p.end(), kZero) != p.end();
    long first = kAny;
    for (long i : p)
      if (i >= 0) {
        first = i;
        break;
      }
    bool same = !zeros;
    for (long i : p) same = same && (i == kAny || i == first);
    for (size_t l = 0; l < 4; ++l) {
      const long own = src.lo * 4 + static_cast<long>(l);
      const long partner = p[l ^ 1];
      if (full[l] == kAny) {
        // A broadcast's lanes stay one index, one vector's lanes in place; else a lane takes its half's other
        // lane, so that each half keeps reading one vector.
        full[l] = same ? first : src.size() == 1 && own < static_cast<long>(n_) ? own : partner >= 0 ? partner : first;
        signs[l] = partner >= 0 ? s[l ^ 1] : 1;
      }
    }
    bool broadcast = true;
    for (long i : full) broadcast = broadcast && i == full[0];
    const Insertion ins = plus && !zeros && src.size() == 2 && !halves(p, [](size_t, long i) { return i / 4; })
                              ? insertion(p)
                              : Insertion{};
    std::string e;
    if (ins.lane >= 0) {
      // One vector in place but for one lane taken from the other (vinsertps, one cycle).
      for (size_t l = 0; l < 4; ++l) full[l] = ins.base * 4 + static_cast<long>(l);
      full[static_cast<size_t>(ins.lane)] = p[static_cast<size_t>(ins.lane)];
      e = "insert<" + std::to_string(ins.lane) + ", " + std::to_string(p[static_cast<size_t>(ins.lane)] % 4) + ">(" +
          use(ins.base) + ", " + use(p[static_cast<size_t>(ins.lane)] / 4) + ")";
      ++ops;
    } else if (zeros && (!plus || src.size() > 1)) {
      // The lanes that hold 0 set by a shuffle of the shuffle without them, with its signs.
      Pattern inner = p;
      for (long& i : inner)
        if (i == kZero) i = kAny;
      Signs inner_signs = s;
      for (size_t l = 0; l < 4; ++l)
        if (p[l] == kZero) inner_signs[l] = 1;
      const std::string from = make(inner, inner_signs, body, ops);
      e = "perm<";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + std::to_string(full[l] == kZero ? 4 : static_cast<long>(l));
      e += ">(" + from + ", v4{})";
      ++ops;
    } else if (!plus && src.size() == 1) {
      // Each lane from the vector or from its negation.
      const long v = src.lo;
      if (negated_.insert(v).second) {
        body += "  const v4 n" + name_ + std::to_string(v) + " = -" + use(v) + ";\n";
        ++ops;
      }
      e = "perm<";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + std::to_string(full[l] % 4 + (signs[l] < 0 ? 4 : 0));
      e += ">(" + use(v) + ", n" + name_ + std::to_string(v) + ")";
      ++ops;
    } else if (!plus) {
      e = "flip(" + make(p, kPlus, body, ops) + ", u4{";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + (signs[l] < 0 ? "0x80000000u" : "0u");
      e += "})";
      ++ops;
    } else if (broadcast) {
      e = "splat<" + std::to_string(full[0] % 4) + ">(" + use(full[0] / 4) + ")";
      ++ops;
    } else if (src.size() <= 2) {
      const long lo = src.lo, hi = src.hi;
      e = "perm<";
      for (size_t l = 0; l < 4; ++l)
        e += std::string(l ? ", " : "") + std::to_string(full[l] == kZero ? 4 : full[l] % 4 + (full[l] / 4 == hi && hi != lo ? 4 : 0));
      e += ">(" + use(lo) + ", " + (zeros ? std::string("v4{}") : use(hi)) + ")";
      ++ops;
    } else {
      e = "v4{";
      for (size_t l = 0; l < 4; ++l) e += std::string(l ? ", " : "") + name_ + "[" + std::to_string(full[l]) + "]";
      e += "}";
      ops += 3;
    }
    const std::string name = "s" + name_ + std::to_string(made_.size());
    body += "  const v4 " + name + " = " + e + ";\n";
    made_.emplace_back(full, signs);
    names_.push_back(name);
    --depth_;
    if (top) extra_ += priced - static_cast<long>(ops - ops_before);
    return name;
  }

  // The loads of the operand's vectors that statements read.
  std::string loads() const {
    // A normalized versor's sandwich can be a constant, or b whatever a is: the operand goes unread.
    if (loaded_.empty()) return "  (void)" + name_ + ";\n";
    std::string s;
    for (long g : loaded_) {
      const long w = std::min<long>(4, static_cast<long>(n_) - 4 * g);
      s += "  const v4 " + name_ + std::to_string(g) + " = load<" + std::to_string(w) + ">(" + name_ + " + " + std::to_string(4 * g) + ");\n";
    }
    return s;
  }

  static bool empty(const Pattern& p) { return p[0] == kAny && p[1] == kAny && p[2] == kAny && p[3] == kAny; }

  // What the shuffles made cost beyond one operation each (the estimate of instructions less `ops`).
  long extra() const { return extra_; }

 private:
  // Whether lanes 0 and 1 read one source and lanes 2 and 3 another, by `source` of each lane that matters.
  template <class F>
  static bool halves(const Pattern& p, F source) {
    for (size_t h = 0; h < 4; h += 2)
      if (p[h] >= 0 && p[h + 1] >= 0 && source(h, p[h]) != source(h + 1, p[h + 1])) return false;
    return true;
  }

  // Where p is one vector in its own lane order but for one lane that another vector gives: that vector and the
  // lane (lane -1 where p is not).
  struct Insertion {
    long base = -1, lane = -1;
  };
  static Insertion insertion(const Pattern& p) {
    const Sources src = sources(p);
    if (src.size() != 2) return {};
    for (long base : {src.lo, src.hi}) {
      long odd = -1;
      int count = 0;
      for (size_t l = 0; l < 4; ++l) {
        if (p[l] < 0) continue;
        if (p[l] / 4 == base && p[l] % 4 == static_cast<long>(l)) continue;
        odd = static_cast<long>(l);
        ++count;
      }
      if (count == 1 && p[static_cast<size_t>(odd)] / 4 != base) return {base, odd};
    }
    return {};
  }

  // The operand's vectors a pattern reads: how many, the first and the last.
  struct Sources {
    int n = 0;
    long lo = 0, hi = 0;
    size_t size() const { return static_cast<size_t>(n); }
  };
  static Sources sources(const Pattern& p) {
    uint64_t mask = 0;
    for (long i : p)
      if (i >= 0) mask |= uint64_t{1} << (i / 4);
    Sources s;
    s.n = std::popcount(mask);
    if (mask) {
      s.lo = std::countr_zero(mask);
      s.hi = 63 - std::countl_zero(mask);
    }
    return s;
  }

  std::string use(long g) {
    loaded_.insert(g);
    return name_ + std::to_string(g);
  }

  std::string name_;
  size_t n_;
  std::vector<std::pair<Pattern, Signs>> made_;
  std::vector<std::string> names_;
  std::set<long> loaded_;
  std::set<long> negated_;
  long extra_ = 0;
  int depth_ = 0;
};

}  // namespace cgagen::library::shuffles
