// The -O2 common-subexpression passes: the state they share and one entry point per pass. The order they
// run in is listed once, in pipeline.cpp's pass table (kPasses, which run_cse iterates); each pass lives in
// its own pass_*.cpp.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "opt/internal.hpp"

namespace cgagen::opt::detail {

// The program under optimization: temporaries in evaluation order (the output roots are passed alongside),
// the names every symbol prints as (the canonical keys order by them) and the counter for new temporaries.
struct CseState {
  CseState(const std::vector<KernelInput>& inputs, const std::vector<Temp>& initial);
  CseState(const CseState&) = delete;  // keys refers to names
  CseState& operator=(const CseState&) = delete;

  // A new temporary t<counter> with the given value (not yet placed in temps).
  Temp make_temp(const GiNaC::ex& value);

  std::map<std::string, GiNaC::ex> inner_sums;  // pass_factor_sums: its shared inner sums by key
  Namer namer;
  SymbolNames names;
  CanonicalKeys keys;
  std::vector<Temp> temps;
  std::map<GiNaC::ex, std::vector<GiNaC::ex>, GiNaC::ex_is_less> cores;  // pass_pair_products: product atoms
  int counter = 0;
};

// One row of the pass table: a pass's name (cgagen --passes), what it does, and its function.
struct Pass {
  const char* name;
  const char* description;
  void (*run)(CseState& st, std::vector<GiNaC::ex>& roots);
};
// The -O2 pipeline, in run order (pipeline.cpp).
extern const std::vector<Pass> kPasses;

// Runs every pass of kPasses in order; roots are the output slot expressions (in order).
void run_cse(CseState& st, std::vector<GiNaC::ex>& roots);

// Pipeline steps (pipeline.cpp).
void orient_all(CseState& st, std::vector<GiNaC::ex>& roots);
void topo_sort(CseState& st);

// The passes, one per file.
void pair_products(CseState& st, std::vector<GiNaC::ex>& roots);      // pass_pair_products.cpp
void half_powers(CseState& st, std::vector<GiNaC::ex>& roots);        // pass_half_powers.cpp
void shared_subtrees(CseState& st, std::vector<GiNaC::ex>& roots);    // pass_shared_subtrees.cpp
void fold_negations(CseState& st, std::vector<GiNaC::ex>& roots);     // pass_negations.cpp
void inline_single_use(CseState& st, std::vector<GiNaC::ex>& roots);  // pass_inline.cpp
void integer_powers(CseState& st, std::vector<GiNaC::ex>& roots);     // pass_integer_powers.cpp
void drop_aliases(CseState& st, std::vector<GiNaC::ex>& roots);       // pass_aliases.cpp
void factor_all_sums(CseState& st, std::vector<GiNaC::ex>& roots);    // pass_factor_sums.cpp
void merge_equal_temps(CseState& st, std::vector<GiNaC::ex>& roots);  // pass_merge_equal.cpp
// pass_numeric_factors.cpp, run by pass_factor_sums on each sum it leaves.
GiNaC::ex group_numeric_factors(CseState& st, const GiNaC::ex& sum, std::vector<Temp>& out);
GiNaC::numeric numeric_factor(const GiNaC::ex& term);

// Product cores shared by the pair pass and the subtree pass: a product without its numeric factor.
GiNaC::ex core_of(const GiNaC::ex& m);

}  // namespace cgagen::opt::detail
