// The -O2 pass pipeline: the pass table (the order in which the common-subexpression passes run, one pass
// per file, pass_*.cpp, each with its name and description for cgagen --passes), and the bookkeeping they
// share (CseState, cse.hpp).
#include <algorithm>
#include <functional>
#include <stdexcept>

#include "opt/cse.hpp"
#include "opt/passes.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

CseState::CseState(const std::vector<KernelInput>& inputs, const std::vector<Temp>& initial)
    : namer(inputs), keys(names) {
  for (const auto& in : inputs)
    for (const auto& s : in.symbols) names[s] = s.get_name();
  for (const auto& t : initial) {
    names[t.sym] = namer.fresh(t.name);
    temps.push_back(t);
  }
}

Temp CseState::make_temp(const ex& value) {
  realsymbol s("t" + std::to_string(counter++));
  std::string name = namer.fresh(s.get_name());
  names[s] = name;
  return Temp{name, s, value};
}

// Every expression with its sums oriented by the keys (lower/lower.hpp), so that equal subexpressions are equal
// trees whatever signs GiNaC's hash-dependent term order gave them.
void orient_all(CseState& st, std::vector<ex>& roots) {
  for (auto& t : st.temps) t.value = orient_sums(t.value, st.keys);
  for (auto& r : roots) r = orient_sums(r, st.keys);
}

// Orders the temporaries so that each comes after those it uses (stable otherwise).
void topo_sort(CseState& st) {
  symbolic::ExHashMap<size_t> index;
  for (size_t i = 0; i < st.temps.size(); ++i) index[st.temps[i].sym] = i;
  std::vector<int> state(st.temps.size(), 0);
  std::vector<Temp> out;
  std::function<void(size_t)> visit = [&](size_t i) {
    if (state[i] == 2) return;
    if (state[i] == 1) throw std::logic_error("cgagen optimizer: cyclic temporaries");
    state[i] = 1;
    ExSet syms;
    collect_symbols(st.temps[i].value, syms);
    std::vector<size_t> deps;
    for (const auto& s : syms)
      if (auto it = index.find(s); it != index.end()) deps.push_back(it->second);
    std::sort(deps.begin(), deps.end());
    for (size_t d : deps) visit(d);
    state[i] = 2;
    out.push_back(st.temps[i]);
  };
  for (size_t i = 0; i < st.temps.size(); ++i) visit(i);
  st.temps = std::move(out);
}

// The pipeline. Sharing passes first (pairs, then whole subtrees), sign clean-up, inlining of what ended up
// used once, sum factoring (a factored form hides products from the sharing passes), and last the merging of
// temporaries that came out equal. Sums are oriented again after each pass that builds new ones.
const std::vector<Pass> kPasses = {
    {"orient", "orient every sum by canonical key (first term positive), so equal subexpressions are equal trees",
     orient_all},
    {"pair-products", "extract the factor pair shared by most products, repeatedly (squares included)",
     pair_products},
    {"sort", "order the temporaries so that each comes after those it uses", [](CseState& st, std::vector<ex>&) {
       topo_sort(st);
     }},
    {"orient", "orient the sums again (the pair products changed them)", orient_all},
    {"half-powers", "give the half-integer powers y^(k/2) of one base one shared square root", half_powers},
    {"shared-subtrees", "make each subtree used twice or more a temporary (products keyed without their number)",
     shared_subtrees},
    {"orient", "orient the sums again (new temporaries)", orient_all},
    {"fold-negations", "store negated temporaries positive; their users subtract", fold_negations},
    {"inline-single-use", "put a temporary used once back into its user; drop unused ones", inline_single_use},
    {"factor-sums", "factor each sum by its most shared symbols, share inner sums, group common numeric factors",
     factor_all_sums},
    {"integer-powers", "build the integer powers of a symbol from each other (x^4 = x^2 x^2), when that is shorter",
     integer_powers},
    {"drop-aliases", "replace a temporary that is one symbol or number by its value", drop_aliases},
    {"orient", "orient the sums again (factored sums)", orient_all},
    {"fold-negations", "store negated temporaries positive again (after factoring)", fold_negations},
    {"merge-equal", "merge temporaries equal to an earlier one or to its negation", merge_equal_temps},
};

void run_cse(CseState& st, std::vector<ex>& roots) {
  for (const Pass& pass : kPasses) {
    PhaseTimer t(std::string("  cse ") + pass.name);
    pass.run(st, roots);
  }
}

}  // namespace cgagen::opt::detail

namespace cgagen::opt {

std::vector<PassInfo> pass_table() {
  std::vector<PassInfo> out;
  for (const auto& p : detail::kPasses) out.push_back({p.name, p.description});
  return out;
}

}  // namespace cgagen::opt
