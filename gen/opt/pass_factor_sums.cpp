// -O2 pass "sum factoring": a symbol that is a direct factor of several terms of a sum is taken out of
// them (ab + ac + ad -> a (b + c + d)), inner sums shared as temporaries; then the numeric-factor pass
// (pass_numeric_factors.cpp) groups terms by their numeric factor.
#include <algorithm>
#include <map>
#include <string>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

class FactorSums {
 public:
  explicit FactorSums(CseState& s) : st(s) {}
  // Every sum of the program factored (factor_sum), innermost first. Runs last, on the sums the sharing
  // passes left: a factored form hides products from them.
  void factor_all_sums(std::vector<ex>& roots) {
    ExMemo memo;
    std::vector<Temp> out;
    for (auto t : st.temps) {
      t.value = factor_sums(t.value, memo, out);
      out.push_back(t);
    }
    for (auto& r : roots) r = factor_sums(r, memo, out);
    st.temps = std::move(out);
  }

  ex factor_sums(const ex& e, ExMemo& memo, std::vector<Temp>& out) {
    if (is_atomic(e)) return e;
    if (auto it = memo.find(e); it != memo.end()) return it->second;
    std::vector<ex> children = ordered_children(e, st.keys);  // in key order: temporaries are made in that order
    ExMemo done;
    for (const ex& c : children) done[c] = factor_sums(c, memo, out);
    struct F : map_function {
      const ExMemo* done;
      ex operator()(const ex& x) override {
        auto it = done->find(x);
        return it == done->end() ? x : it->second;
      }
    } f;
    f.done = &done;
    ex r = e.map(f);
    if (is_a<add>(r)) r = factor_sum(r, out);
    memo[e] = r;
    return r;
  }

  // The symbols that are direct factors of a term (not under a power): those of a product, or the term
  // itself when it is a bare symbol. A bare symbol must count: GiNaC's hash order (which moves with ASLR)
  // decides whether a sum inside a product reads t - t*d or -t + t*d, and -t is a product, t is not; counting
  // only products made the factoring (and the kernel) differ from process to process.
  static std::vector<ex> direct_symbols(const ex& term) {
    std::vector<ex> out;
    if (is_a<symbol>(term)) out.push_back(term);
    if (is_a<mul>(term))
      for (size_t i = 0; i < term.nops(); ++i)
        if (is_a<symbol>(term.op(i))) out.push_back(term.op(i));
    return out;
  }

  // One sum: first a symbol that is a direct factor of several terms is taken out of them (greedy, the most
  // shared first: ab + ac + ad -> a (b + c + d), 2 mul fewer), the inner sums treated the same way; then the
  // terms sharing a numeric factor are grouped.
  ex factor_sum(const ex& sum, std::vector<Temp>& out) {
    const ex r = factor_symbols(sum, out);
    return is_a<add>(r) ? group_numeric_factors(st, r, out) : r;
  }

  // A sum with the symbols that several terms share taken out (see factor_sum).
  ex factor_symbols(const ex& sum, std::vector<Temp>& out) {
    std::vector<ex> terms = ordered_children(sum, st.keys);
    // Sums are built once from their terms: adding terms one by one to an ex re-sorts the sum every time
    // (quadratic in its length, seconds on the few-thousand-term sums of a long chain).
    exvector factored;
    for (;;) {
      std::map<ex, int, ex_is_less> uses;
      for (const ex& t : terms)
        for (const ex& a : direct_symbols(t)) ++uses[a];
      ex best;
      int best_uses = 1;
      for (const auto& [a, n] : uses)  // ties: the smaller key, so the choice does not depend on GiNaC's order
        if (n > best_uses || (n == best_uses && n > 1 && st.keys.less(a, best))) best = a, best_uses = n;
      if (best_uses < 2) break;
      exvector inner_terms;
      std::vector<ex> rest;
      for (const ex& t : terms) {
        const auto syms = direct_symbols(t);
        if (std::any_of(syms.begin(), syms.end(), [&](const ex& a) { return a.is_equal(best); }))
          inner_terms.push_back(t / best);
        else
          rest.push_back(t);
      }
      ex inner = dynallocate<add>(inner_terms);
      if (is_a<add>(inner)) {
        // The inner sum factored the same way; a numeric factor all its terms share goes in front of the
        // product (c a (b + d) rather than a (c b + c d)), where GiNaC keeps it undistributed.
        inner = factor_symbols(orient_sums(inner, st.keys), out);
        const numeric c = is_a<add>(inner) ? common_numeric_factor(inner) : numeric(1);
        factored.push_back(c * best * inner_sum(orient_sums(inner / c, st.keys), out));
      } else {
        factored.push_back(best * inner);
      }
      terms = std::move(rest);
    }
    factored.insert(factored.end(), terms.begin(), terms.end());
    return orient_sums(dynallocate<add>(factored), st.keys);
  }

  // An inner sum of factor_symbols as a temporary, one per distinct sum (by canonical key): the same
  // (a + b) c comes out of several outputs. Keyed by text, not by GiNaC's structural order, so that which
  // sums are shared cannot depend on hash order.
  ex inner_sum(const ex& sum, std::vector<Temp>& out) {
    if (!is_a<add>(sum)) return sum;
    ex oriented = sum;
    int sign = 1;
    if (st.keys.sign(oriented) < 0) oriented = -oriented, sign = -1;
    const std::string& key = st.keys.key(oriented);
    auto it = st.inner_sums.find(key);
    if (it == st.inner_sums.end()) {
      Temp t = st.make_temp(oriented);
      out.push_back(t);
      it = st.inner_sums.emplace(key, t.sym).first;
    }
    return sign * it->second;
  }

  // |c| when every term of the sum has the numeric factor +-c, else 1.
  static numeric common_numeric_factor(const ex& sum) {
    numeric c = abs(numeric_factor(sum.op(0)));
    for (size_t i = 1; i < sum.nops(); ++i)
      if (!abs(numeric_factor(sum.op(i))).is_equal(c)) return 1;
    return c.is_zero() ? numeric(1) : c;
  }

 private:
  CseState& st;
};

}  // namespace

void factor_all_sums(CseState& st, std::vector<ex>& roots) { FactorSums(st).factor_all_sums(roots); }

}  // namespace cgagen::opt::detail
