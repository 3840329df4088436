// -O2 pass "shared subtrees": a hash-consed subexpression used at least twice becomes a temporary.
#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

class SharedSubtrees {
 public:
  explicit SharedSubtrees(CseState& s) : st(s) {}
  // Hash-consed subtrees used at least twice become temporaries.
  static ex node_of(const ex& e) {
    if (is_a<mul>(e)) {
      for (size_t i = 0; i < e.nops(); ++i)
        if (is_a<numeric>(e.op(i))) return core_of(e);
    }
    return e;
  }

  void count_uses(const ex& e, symbolic::ExHashMap<int>& uses) {
    if (is_atomic(e)) return;
    ex n = node_of(e);
    if (is_atomic(n)) return;
    if (++uses[n] > 1) return;
    for (const ex& c : ordered_children(n, st.keys)) {
      count_uses(c, uses);
      // An integer power prints its base several times.
      if (is_a<power>(n) && !is_atomic(c) && is_a<numeric>(n.op(1)) && ex_to<numeric>(n.op(1)).is_integer() &&
          abs(ex_to<numeric>(n.op(1))) >= 2 && c.is_equal(n.op(0)))
        count_uses(c, uses);
    }
  }

  ex share(const ex& e, const symbolic::ExHashMap<int>& uses, ExMemo& memo, std::vector<Temp>& out) {
    if (is_atomic(e)) return e;
    auto it = memo.find(e);
    if (it != memo.end()) return it->second;
    ex n = node_of(e);
    ex r;
    if (!n.is_equal(e)) {
      r = (e / n) * share(n, uses, memo, out);  // e / n is the numeric coefficient
    } else {
      for (const ex& c : ordered_children(e, st.keys)) share(c, uses, memo, out);
      struct F : map_function {
        SharedSubtrees* self;
        const symbolic::ExHashMap<int>* uses;
        ExMemo* memo;
        std::vector<Temp>* out;
        ex operator()(const ex& x) override { return self->share(x, *uses, *memo, *out); }
      } f;
      f.self = this, f.uses = &uses, f.memo = &memo, f.out = &out;
      r = e.map(f);
      auto u = uses.find(e);
      if (u != uses.end() && u->second >= 2 && count_ops(r, st.keys).total() > 0) {
        Temp t = st.make_temp(r);
        out.push_back(t);
        r = t.sym;
      }
    }
    memo[e] = r;
    return r;
  }

  void shared_subtrees(std::vector<ex>& roots) {
    symbolic::ExHashMap<int> uses;
    for (const auto& t : st.temps) count_uses(t.value, uses);
    for (const auto& r : roots) count_uses(r, uses);
    ExMemo memo;
    std::vector<Temp> out;
    for (auto t : st.temps) {
      t.value = share(t.value, uses, memo, out);
      out.push_back(t);
    }
    for (auto& r : roots) r = share(r, uses, memo, out);
    st.temps = std::move(out);
  }

 private:
  CseState& st;
};

}  // namespace

void shared_subtrees(CseState& st, std::vector<ex>& roots) { SharedSubtrees(st).shared_subtrees(roots); }

}  // namespace cgagen::opt::detail
