// -O1: the substituted, expanded output coefficients (and the materialized values as temporaries); past the
// size budget (kMaxExpandedNodes) the script's statement form instead, which -O2 also builds as a candidate.
#include "opt/levels.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

StatementForm statement_form(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  StatementForm f;
  exmap atomic;
  const ValueNames names(k);
  for (size_t vi = 0; vi < k.values.size(); ++vi) {
    const auto& v = k.values[vi];
    for (size_t i = 0; i < v.blades.size(); ++i)
      if (s.needed.count(v.symbols[i])) {
        ex c = canonical(atomic.empty() ? v.coeffs[i] : v.coeffs[i].subs(atomic, kSymbolSubs)).value();
        if (is_atomic(c))
          atomic[v.symbols[i]] = c;
        else
          f.temps.push_back({names.of(vi, i), v.symbols[i], c});
      }
  }
  for (const auto& slots : plans)
    for (const auto& sp : slots) {
      auto it = atomic.find(sp.value_sym);
      f.roots.push_back(it == atomic.end() ? sp.value_sym : it->second);
    }
  return f;
}

// The size (printed_size) of the expanded (-O1) form: what the CSE passes and the printer would work through.
size_t expanded_size(const std::vector<Temp>& kept, const std::vector<std::vector<SlotPlan>>& plans) {
  size_t n = 0;
  for (const auto& slots : plans)
    for (const auto& sp : slots) n += printed_size(sp.value.num) + printed_size(sp.value.den);
  for (const auto& t : kept) n += printed_size(t.value);
  return n;
}

std::string over_budget_note(const char* level, size_t size, bool over_count) {
  return std::string(level) + " kept the script's statement form: the expanded form has " +
         (over_count ? "more than " + std::to_string(kMaxCountedNodes) : std::to_string(size)) +
         " symbol occurrences (budget " + std::to_string(kMaxExpandedNodes) + ")";
}

Program optimize_o1(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  Program p = skeleton(k, Level::O1);
  p.temps = materialized_temps(k, s);
  const size_t size = s.over_count ? 0 : expanded_size(p.temps, plans);
  if (s.over_count || size > kMaxExpandedNodes) {
    StatementForm f = statement_form(k, s, plans);
    p.temps = std::move(f.temps);
    p.notes.push_back(over_budget_note("-O1", size, s.over_count));
    size_t ri = 0;
    for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
      ProgramOutput po{k.outputs[oi].name, {}};
      for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, f.roots.at(ri++)});
      p.outputs.push_back(std::move(po));
    }
    drop_unread_temps(p);
    return p;
  }
  for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
    ProgramOutput po{k.outputs[oi].name, {}};
    for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, sp.value.value()});
    p.outputs.push_back(std::move(po));
  }
  drop_unread_temps(p);
  return p;
}
}  // namespace cgagen::opt::detail
