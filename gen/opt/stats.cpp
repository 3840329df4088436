// Op counts of a Program (--stats and the -O2 cost model): per output with the temporaries it needs, and
// for the whole program.
#include <set>

#include "opt/internal.hpp"
#include "opt/program.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using namespace detail;

SymbolNames symbol_names(const Program& program) {
  SymbolNames names;
  for (const auto& in : program.inputs)
    for (const auto& s : in.symbols) names[s] = s.get_name();
  for (const auto& t : program.temps) names[t.sym] = t.name;
  return names;
}

ProgramStats program_stats(const Program& p) {
  SymbolNames names = symbol_names(p);
  CanonicalKeys keys(names);
  ProgramStats st;
  st.temp_count = p.temps.size();
  std::map<ex, size_t, ex_is_less> index;
  std::vector<OpCounts> temp_ops;
  for (size_t i = 0; i < p.temps.size(); ++i) {
    index[p.temps[i].sym] = i;
    temp_ops.push_back(count_ops(p.temps[i].value, keys));
    st.temps += temp_ops.back();
  }
  // The temporaries an expression reads directly; each temporary's once, so that the closure per output
  // below is a walk over indices (a chain of thousands of temporaries read by as many outputs).
  auto direct = [&](const ex& e) {
    ExSet syms;
    collect_symbols(e, syms);
    std::vector<size_t> out;
    for (const auto& s : syms)
      if (auto it = index.find(s); it != index.end()) out.push_back(it->second);
    return out;
  };
  std::vector<std::vector<size_t>> reads(p.temps.size());
  for (size_t i = 0; i < p.temps.size(); ++i) reads[i] = direct(p.temps[i].value);
  std::vector<size_t> seen(p.temps.size(), 0);  // the output (1-based) that last visited each temporary
  st.total = st.temps;
  for (const auto& o : p.outputs) {
    OpCounts own;
    const size_t mark = st.outputs.size() + 1;
    std::vector<size_t> todo;
    for (const auto& slot : o.slots) {
      own += count_ops(slot.value, keys);
      for (size_t i : direct(slot.value)) todo.push_back(i);
    }
    st.total += own;
    while (!todo.empty()) {
      const size_t i = todo.back();
      todo.pop_back();
      if (seen[i] == mark) continue;
      seen[i] = mark;
      own += temp_ops[i];
      for (size_t j : reads[i])
        if (seen[j] != mark) todo.push_back(j);
    }
    st.outputs.push_back({o.name, own});
  }
  return st;
}

}  // namespace cgagen::opt
