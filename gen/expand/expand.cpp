// The expander's run over a script: statements, macros and calls; and expand(), the stage's entry (expand.hpp).
// The class and the map of its files: expander.hpp.
#include "expand/expand.hpp"

#include <cstdio>
#include <cstdlib>

#include "expand/expander.hpp"

namespace cgagen::expand_detail {

Kernel Expander::run(const front::Script& script) {
  symbolic::NodeCacheScope caches;
  size_t spent = 0;
  define_algebra_builtins();
  for (const auto& [loc, message] : script.warnings) kernel_.warnings.push_back({loc, message});
  collect_script_names(script.statements);
  for (const auto& s : script.statements) {
    // GiNaC's own faults (a pole, an overflow) anywhere in a statement become a diagnostic, not a crash.
    // The work budget is per statement: a script of many small statements compiles in time linear in
    // its length, and only a statement that is itself too large is refused.
    try {
      symbolic::WorkBudget budget;
      statement_name_ = s->kind == Stmt::Kind::Assign ? s->name : "statement";
      exec_top(*s);
      spent += budget.spent();
    } catch (const CompileError&) {
      throw;
    } catch (const symbolic::BudgetExceeded& ex) {
      std::string what = s->kind == Stmt::Kind::Assign ? "statement '" + s->name + "'" : "this statement";
      throw CompileError(s->loc, what + " is over cgagen's work budget: " + ex.what() +
                                     "; split it into smaller statements or give fewer blades");
    } catch (const std::exception& ex) {
      throw CompileError(s->loc, std::string("cannot evaluate: ") + ex.what());
    }
  }
  if (std::getenv("CGAGEN_TIMING")) std::fprintf(stderr, "cgagen budget: %zu terms\n", spent);
  for (const auto& v : pragmas_.versors())
    if (!globals_.count(v.name))
      throw CompileError(v.loc, "'#pragma versor': '" + v.name + "' is neither an input nor a name the script assigns");
  finish_outputs();
  pragmas_.apply_in2out(kernel_);
  apply_jacobians();  // after in2out: the derivative outputs follow the ordered ones
  drop_unused_values();
  kernel_.shared_products = words_.report();
  return std::move(kernel_);
}

void Expander::define_algebra_builtins() {
  const std::string text = expand_algebra::prelude();
  if (text.empty()) return;
  prelude_file_ = std::make_unique<front::SourceFile>("<" + algebra::current().name() + " built-ins>", text);
  prelude_ = std::make_unique<front::Script>(front::parse(*prelude_file_));
  for (const auto& s : prelude_->statements) define_macro(*s);
}

bool Expander::is_algebra_builtin(const Stmt* def) const {
  if (!prelude_) return false;
  for (const auto& s : prelude_->statements)
    if (s.get() == def) return true;
  return false;
}

// Every name the script assigns or defines as a macro, inside if/else branches too; and every name its
// statements assign or read (Gaalop's inliner sees the whole script, macro bodies and if conditions aside).
void Expander::collect_script_names(const std::vector<front::StmtPtr>& statements) {
  std::function<void(const Expr&)> reads = [&](const Expr& x) {
    if (x.kind == Expr::Kind::Name) inlined_taken_.insert(x.text);
    for (const auto& a : x.args)
      if (a) reads(*a);
  };
  for (const auto& s : statements) {
    if (s->kind == Stmt::Kind::Assign || s->kind == Stmt::Kind::MacroDef) script_names_.insert(s->name);
    if (s->kind == Stmt::Kind::Assign) inlined_taken_.insert(s->name);
    if ((s->kind == Stmt::Kind::Assign || s->kind == Stmt::Kind::ExprStmt) && s->value) reads(*s->value);
    if (s->kind == Stmt::Kind::If) {
      collect_script_names(s->body);
      collect_script_names(s->else_body);
    }
  }
}

// Gaalop's Inliner.createNewVariable: "macro_" + M + "_" + k, else that name with the first free number
// appended. Names only ever become taken, so the search for a name resumes where the last one stopped.
std::string Expander::inlined_name(const std::string& macro, const std::string& local) {
  const std::string base = "macro_" + macro + "_" + local;
  std::string name = base;
  if (inlined_taken_.count(name)) {
    int& k = inlined_suffix_[base];
    if (k == 0) k = 1;
    while (inlined_taken_.count(base + std::to_string(k))) ++k;
    name = base + std::to_string(k);
  }
  inlined_taken_.insert(name);
  return name;
}

void Expander::exec_top(const Stmt& s) {
  switch (s.kind) {
    case Stmt::Kind::Pragma:
      if (!assigned_in_branch_.empty())
        throw CompileError(s.loc, "'#pragma' inside if/else is not supported: put it before the 'if'");
      pragmas_.apply(s, kernel_, *this);
      return;
    case Stmt::Kind::MacroDef: define_macro(s); return;
    case Stmt::Kind::ExprStmt: eval(*s.value); return;
    case Stmt::Kind::If: exec_if(s); return;
    case Stmt::Kind::Assign: break;
  }
  if (s.value && pragmas_.normalize_outputs() && s.marker == front::Marker::Output) {
    // #pragma normalize: x_unnormalized = e; ?x = x_unnormalized / abs(x_unnormalized);
    check_assignable(s);
    Stmt raw = s;
    raw.name = s.name + "_unnormalized";
    raw.marker = front::Marker::None;
    record_value(raw, eval(*s.value));
    const Multivector& u = globals_.at(raw.name);
    record_value(s, divide(u, magnitude(u), *s.value));
  } else if (s.value) {
    check_assignable(s);
    statement_value_ = s.value.get();
    statement_word_.reset();
    Multivector v = eval(*s.value);
    statement_value_ = nullptr;
    record_value(s, v);
    // A name bound to a product chain stands for its word: later chains reuse it (expand/words.hpp).
    if (statement_word_) words_.remember(statement_word_->first, statement_word_->second, globals_.at(s.name), s.name);
  } else if (!globals_.count(s.name) && !last_value_.count(s.name)) {
    throw CompileError(s.loc, "output '" + s.name + "' is never assigned");
  }
  if (s.marker == front::Marker::Output || s.marker == front::Marker::Visual) mark(s.name, s.loc);
}

void Expander::exec_local(const Stmt& s) {
  switch (s.kind) {
    case Stmt::Kind::If:
      throw CompileError(s.loc, "if/else inside a macro is not supported: put the 'if' around the macro's call");
    case Stmt::Kind::Pragma: throw CompileError(s.loc, "'#pragma' is not allowed inside a macro");
    case Stmt::Kind::MacroDef: define_macro(s); return;
    case Stmt::Kind::ExprStmt: eval(*s.value); return;
    case Stmt::Kind::Assign: break;
  }
  const bool output = s.marker == front::Marker::Output || s.marker == front::Marker::Visual;
  if (!s.value) {
    // "?k;" inside a macro: the local's current value becomes an output, as in Gaalop.
    if (!output) return;
    auto it = frames_.back().locals.find(s.name);
    if (it == frames_.back().locals.end()) throw CompileError(s.loc, "output '" + s.name + "' is never assigned");
    macro_output(s, it->second);
    return;
  }
  check_assignable(s);
  Multivector v = eval(*s.value);
  frames_.back().locals[s.name] = v;
  if (output) macro_output(s, v);  // "?k = e;" inside a macro: also an output (Gaalop's QuestionLineMacro)
}

// An output marked inside a macro, under the name this call gave the local (inlined_name).
void Expander::macro_output(const Stmt& s, const Multivector& v) {
  Stmt out = s;
  out.name = frames_.back().inlined.at(s.name);
  record_value(out, v, /*bind=*/false);
  mark(out.name, s.loc);
}

void Expander::check_assignable(const Stmt& s) {
  if (is_basis_name(s.name)) throw CompileError(s.loc, "cannot assign to basis vector '" + s.name + "'");
  if (macros_.count(s.name)) throw CompileError(s.loc, "cannot assign to '" + s.name + "': it is a macro");
}

void Expander::define_macro(const Stmt& s) {
  if (is_basis_name(s.name)) throw CompileError(s.loc, "cannot define a macro named '" + s.name + "'");
  macros_[s.name][macro_arity(s)] = &s;
  latest_macro_[s.name] = &s;
}

void Expander::check_arity(const Expr& e, const std::vector<size_t>& arities) {
  if (std::find(arities.begin(), arities.end(), e.args.size()) != arities.end()) return;
  std::string counts;
  for (size_t i = 0; i < arities.size(); ++i)
    counts += (i == 0 ? "" : i + 1 == arities.size() ? " or " : ", ") + std::to_string(arities[i]);
  throw CompileError(e.loc, "'" + e.text + "' takes " + counts + " argument" + (arities.back() == 1 ? "" : "s") +
                                ", got " + std::to_string(e.args.size()));
}

Multivector Expander::call(const Expr& e) {
  const std::string& fn = e.text;
  std::vector<Multivector> args;
  auto macro = macros_.find(fn);
  if (macro != macros_.end()) {
    for (const auto& a : e.args) args.push_back(eval(*a));
    // The definition for this many arguments, else the latest one (which may use fewer).
    auto by_arity = macro->second.find(args.size());
    const Stmt* def = by_arity != macro->second.end() ? by_arity->second : latest_macro_.at(fn);
    if (!is_algebra_builtin(def)) return call_macro(*def, std::move(args), e);
    try {  // a fault inside a built-in macro is reported at the call: its text is not the script's
      return call_macro(*def, std::move(args), e);
    } catch (const CompileError& x) {
      throw CompileError(e.loc, "in the " + algebra::current().name() + " built-in '" + fn + "': " + x.what());
    }
  }
  const expand_builtins::Builtin* builtin = expand_builtins::find(fn);
  if (!builtin) {
    std::vector<std::string> known = expand_builtins::names();  // functions: macros, built-ins (expand/hints.hpp)
    for (const auto& m : macros_) known.push_back(m.first);
    throw CompileError(e.loc, "unknown function '" + fn + "'" + hints::for_call(fn, known));
  }
  if (builtin->cga_only && !expand_algebra::is_cga())
    throw CompileError(e.loc, "'" + fn + "' is a CGA built-in; the algebra '" + algebra::current().name() +
                                  "' does not have it");
  check_arity(e, builtin->arities);
  for (const auto& a : e.args) args.push_back(eval(*a));
  return guarded(e.loc, [&] { return builtin->define(expand_builtins::Call{fn, args, e, *this}); });
}

// The highest _P(n) a macro's body and result use.
size_t Expander::macro_arity(const Stmt& def) {
  size_t n = 0;
  std::function<void(const Expr&)> walk = [&](const Expr& x) {
    if (x.kind == Expr::Kind::MacroArg && x.index > 0) n = std::max(n, static_cast<size_t>(x.index));
    for (const auto& a : x.args)
      if (a) walk(*a);
  };
  for (const auto& st : def.body)
    if (st->value) walk(*st->value);
  if (def.result) walk(*def.result);
  return n;
}

Multivector Expander::call_macro(const Stmt& def, std::vector<Multivector> args, const Expr& e) {
  for (size_t i = 0; i < frames_.size(); ++i) {
    if (frames_[i].def != &def) continue;
    std::string chain;
    for (size_t j = i; j < frames_.size(); ++j) chain += "'" + frames_[j].macro + "' -> ";
    throw CompileError(e.loc, "recursive macro call " + chain + "'" + def.name + "'");
  }
  frames_.push_back({def.name, &def, std::move(args), {}, {}});
  // As Gaalop inlines a call: every local the body assigns gets its own name before the body runs.
  for (const auto& s : def.body)
    if (s->kind == Stmt::Kind::Assign && s->value && !frames_.back().inlined.count(s->name))
      frames_.back().inlined[s->name] = inlined_name(def.name, s->name);
  for (const auto& s : def.body) exec_local(*s);
  Multivector r = def.result ? eval(*def.result) : Multivector();
  frames_.pop_back();
  return r;
}

}  // namespace cgagen::expand_detail

namespace cgagen {

Kernel expand(const front::Script& script, const std::string& kernel_name,
              std::shared_ptr<const algebra::Algebra> algebra, const std::vector<std::string>& jacobian_wrt) {
  algebra::Using in(std::move(algebra));
  expand_detail::Expander x(kernel_name, jacobian_wrt);
  Kernel k = x.run(script);
  k.algebra = algebra::current_shared();
  return k;
}

}  // namespace cgagen
