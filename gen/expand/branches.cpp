// if/else in the expander: both branches expanded, then every name they assign as per-blade selects
// (expander.hpp; docs/language.md, "if / else").
#include "expand/expander.hpp"

namespace cgagen::expand_detail {

void Expander::exec_if(const Stmt& s) {
  const symbolic::Condition cond = condition(*s.value);
  const std::map<std::string, Multivector> before = globals_;
  const size_t inputs_at_if = kernel_.inputs.size();
  struct Branch {
    std::vector<std::string> names;  // in order of assignment, with repeats
    std::map<std::string, Multivector> values;
  };
  auto run_branch = [&](const std::vector<front::StmtPtr>& body) {
    Branch b;
    assigned_in_branch_.push_back(&b.names);
    struct Pop {
      std::vector<std::vector<std::string>*>& stack;
      ~Pop() { stack.pop_back(); }
    } pop{assigned_in_branch_};
    for (const auto& st : body) exec_top(*st);
    for (const auto& n : b.names)
      if (auto it = globals_.find(n); it != globals_.end()) b.values[n] = it->second;
    // Back to the state before the 'if', keeping the inputs a branch introduced (a name read before any
    // assignment is an input wherever it is read).
    globals_ = before;
    for (size_t i = inputs_at_if; i < kernel_.inputs.size(); ++i)
      if (!kernel_.inputs[i].is_multivector) globals_[kernel_.inputs[i].name] = Multivector(kernel_.inputs[i].symbols.at(0));
    return b;
  };
  const Branch then_branch = run_branch(s.body);
  const Branch else_branch = run_branch(s.else_body);
  std::vector<std::string> names;
  for (const Branch* b : {&then_branch, &else_branch})
    for (const auto& n : b->names)
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  for (const auto& n : names) {
    auto side = [&](const Branch& b) {
      if (auto it = b.values.find(n); it != b.values.end()) return it->second;
      if (auto it = globals_.find(n); it != globals_.end()) return it->second;
      return Multivector();
    };
    const Multivector x = side(then_branch), y = side(else_branch);
    std::set<algebra::BladeIndex> blades;
    for (const auto& [b, c] : x.terms()) blades.insert(b);
    for (const auto& [b, c] : y.terms()) blades.insert(b);
    Multivector merged;
    for (auto b : blades) merged.set(b, symbolic::make_select(cond, x.coeff(b), y.coeff(b)));
    Stmt st;
    st.kind = Stmt::Kind::Assign;
    st.loc = s.loc;
    st.name = n;
    record_value(st, merged);
  }
}

// An if condition over scalars.
symbolic::Condition Expander::condition(const Expr& e) {
  using Op = symbolic::Condition::Op;
  symbolic::Condition c;
  if (e.kind == Expr::Kind::Logic) {
    c.op = e.text == "!" ? Op::Not : e.text == "&&" ? Op::And : Op::Or;
    c.l = std::make_shared<symbolic::Condition>(condition(*e.args.at(0)));
    if (c.op != Op::Not) c.r = std::make_shared<symbolic::Condition>(condition(*e.args.at(1)));
    return c;
  }
  if (e.kind == Expr::Kind::Compare) {
    static const std::map<std::string, Op> ops = {{"<", Op::Lt}, {"<=", Op::Le}, {">", Op::Gt},
                                                  {">=", Op::Ge}, {"==", Op::Eq}, {"!=", Op::Ne}};
    c.op = ops.at(e.text);
    c.a = condition_operand(*e.args.at(0));
    c.b = condition_operand(*e.args.at(1));
    return c;
  }
  c.op = Op::Ne;  // a scalar alone: true when nonzero
  c.a = condition_operand(e);
  c.b = 0;
  return c;
}

ex Expander::condition_operand(const Expr& e) {
  const Multivector v = scalar_part_if_scalar(eval(e));
  if (!v.is_scalar())
    throw CompileError(e.loc, "a condition compares scalars; this is " + describe(v) +
                                  " (compare a coefficient, coefficient(v, e1), or a magnitude, abs(v))");
  const ex c = v.scalar();
  if (GiNaC::is_a<GiNaC::numeric>(c) && !GiNaC::ex_to<GiNaC::numeric>(c).is_real())
    throw CompileError(e.loc, "a condition compares real numbers; this one is complex");
  return c;
}

}  // namespace cgagen::expand_detail
