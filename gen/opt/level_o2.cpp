// -O2: several candidate forms of the -O1 result (expanded, collected in the inputs, the same rewritten with
// `#pragma normalized` rules, the script's statement form) each run through the pass pipeline (run_cse,
// pipeline.cpp); the cheapest by weighted op count is kept.
#include "opt/cse.hpp"
#include "opt/levels.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

Program finish_o2(const Kernel& k, std::vector<Temp> in_temps, std::vector<ex> roots,
                  const std::vector<std::vector<SlotPlan>>& plans) {
  CseState cse(k.inputs, in_temps);
  run_cse(cse, roots);
  Program p = skeleton(k, Level::O2);
  p.temps = cse.temps;
  size_t ri = 0;
  for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
    ProgramOutput po{k.outputs[oi].name, {}};
    for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, roots.at(ri++)});
    p.outputs.push_back(std::move(po));
  }
  // Number the temporaries in evaluation order.
  Namer namer(k.inputs);
  for (size_t i = 0; i < p.temps.size(); ++i) p.temps[i].name = namer.fresh("t" + std::to_string(i));
  return p;
}

long program_cost(const Program& p) { return program_stats(p).total.weighted(); }

}  // namespace

Program optimize_o2(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans_in) {
  std::vector<Program> variants;
  const std::vector<std::vector<SlotPlan>>* current = &plans_in;
  auto roots_with = [&](auto&& f) {
    std::vector<ex> roots;
    for (const auto& slots : *current)
      for (const auto& sp : slots) roots.push_back(f(sp));
    return roots;
  };
  const auto& plans = plans_in;
  // 1. The expanded -O1 forms, and 2. the same collected in the inputs, unless the -O1 form is too large
  //    for the CSE passes to finish in time; on such scripts the statement form (3) has always been far
  //    cheaper anyway (paper A.1: 328 against 1516, circle3: 165 against 1402 weighted ops).
  const std::vector<Temp> kept = materialized_temps(k, s);
  const size_t size = s.over_count ? 0 : expanded_size(kept, plans);
  std::vector<std::string> notes;
  if (s.over_count || size > kMaxExpandedNodes) {
    notes.push_back(over_budget_note("-O2", size, s.over_count));
  } else {
    std::vector<std::vector<ex>> groups;
    std::vector<ex> scalars;
    for (const auto& in : k.inputs)
      if (!in.is_multivector) scalars.push_back(in.symbols.at(0));
    if (!scalars.empty()) groups.push_back(scalars);
    for (const auto& in : k.inputs)
      if (in.is_multivector) groups.emplace_back(in.symbols.begin(), in.symbols.end());
    auto add_forms = [&] {
      {
        PhaseTimer t("variant expanded");
        variants.push_back(
            finish_o2(k, kept, roots_with([](const SlotPlan& sp) { return sp.value.value(); }), plans));
      }
      for (const auto& g : groups) {
        std::vector<ex> roots;
        PhaseTimer t("variant collected");
        roots = roots_with([&](const SlotPlan& sp) {
          ex n = collect_in(sp.value.num, g);
          return sp.value.den.is_equal(1) ? n : n / collect_in(sp.value.den, g);
        });
        variants.push_back(finish_o2(k, kept, roots, plans));
      }
    };
    add_forms();
    // The same forms of the outputs rewritten with each choice of normalization rules.
    for (const auto& rules : rule_sets(k)) {
      std::vector<std::vector<SlotPlan>> reduced = plans;
      for (auto& slots : reduced)
        for (auto& sp : slots) sp.value = {reduce_with(sp.value.num, rules), reduce_with(sp.value.den, rules)};
      current = &reduced;
      add_forms();
      current = &plans_in;
    }
  }
  // 3. The script's own statements (each value expanded over earlier values), which keeps products like
  //    (M X) ~M factored.
  {
    StatementForm f = statement_form(k, s, plans);
    PhaseTimer t("variant statements");
    variants.push_back(finish_o2(k, f.temps, f.roots, plans));
  }
  PhaseTimer tc("costs");
  size_t best = 0;
  long best_cost = variants.size() > 1 ? program_cost(variants[0]) : 0;  // one form: nothing to compare
  for (size_t i = 1; i < variants.size(); ++i) {
    long c = program_cost(variants[i]);
    if (c < best_cost) best = i, best_cost = c;
  }
  variants[best].notes = notes;
  return variants[best];
}
}  // namespace cgagen::opt::detail
