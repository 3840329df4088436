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
  std::vector<ExSet> deps;  // each temp's transitive temp dependencies
  for (size_t i = 0; i < p.temps.size(); ++i) {
    index[p.temps[i].sym] = i;
    temp_ops.push_back(count_ops(p.temps[i].value, keys));
    st.temps += temp_ops.back();
  }
  auto temp_deps = [&](const ex& e) {
    std::set<size_t> out, todo;
    ExSet syms;
    collect_symbols(e, syms);
    for (const auto& s : syms)
      if (index.count(s)) todo.insert(index[s]);
    while (!todo.empty()) {
      size_t i = *todo.begin();
      todo.erase(todo.begin());
      if (!out.insert(i).second) continue;
      ExSet s2;
      collect_symbols(p.temps[i].value, s2);
      for (const auto& s : s2)
        if (index.count(s) && !out.count(index[s])) todo.insert(index[s]);
    }
    return out;
  };
  st.total = st.temps;
  for (const auto& o : p.outputs) {
    OpCounts own;
    std::set<size_t> used;
    for (const auto& slot : o.slots) {
      own += count_ops(slot.value, keys);
      auto d = temp_deps(slot.value);
      used.insert(d.begin(), d.end());
    }
    st.total += own;
    for (size_t i : used) own += temp_ops[i];
    st.outputs.push_back({o.name, own});
  }
  return st;
}

}  // namespace cgagen::opt
