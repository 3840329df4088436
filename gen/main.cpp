// cgagen: the command-line tool. CluScript file -> parse -> expand -> optimize -> emit (or --stats, --diff,
// --eval, --dump-ast; or --gpc: a C/C++/CUDA source with GPC blocks, gen/gpc/). Exit codes: 0 success, 1 error in the script (diagnostic on stderr), 2 bad usage.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "algebra/algebra.hpp"
#include "expand/algebra_pragma.hpp"
#include "emit/emit.hpp"
#include "emit/names.hpp"
#include "emit/statements.hpp"
#include "expand/expand.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"
#include "gpc/gpc.hpp"
#include "library/build.hpp"
#include "library/emit.hpp"
#include "library/spec.hpp"
#include "opt/passes.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "opt/stage.hpp"
#include "symbolic/node_cache.hpp"
#include "usage.hpp"

namespace {

using namespace cgagen;


struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  emit::EmitOptions emit;
  opt::Level level = opt::Level::O2;
  std::string output;
  std::string name;
  std::string script;
  bool stats = false;
  std::string stats_out;
  std::optional<std::pair<opt::Level, opt::Level>> diff;
  bool dump_ast = false;
  bool eval = false;
  opt::InputValues eval_inputs;
  bool werror = false;
  std::string algebra = "cga";
  bool algebra_given = false;  // --algebra on the command line (a script's #pragma algebra must agree)
  std::vector<std::string> uniforms;  // --uniform
  std::vector<std::string> stage_at;  // --stage-at
  std::vector<std::string> outputs;   // --outputs (empty: all)
  std::vector<std::string> jacobian;  // --jacobian
  bool gpc = false;                   // --gpc
  bool library = false;               // --library
  std::vector<std::pair<emit::Target, std::string>> also;  // --also TARGET=FILE (--library)
  std::string type;                   // --type (--gpc)
  bool target_given = false;
};

// --outputs: the kernel with only the named outputs (each must be one of the script's).
void keep_outputs(Kernel& kernel, const std::vector<std::string>& names) {
  std::string known;
  for (const auto& out : kernel.outputs) known += (known.empty() ? "" : ", ") + out.name;
  for (const auto& n : names)
    if (std::none_of(kernel.outputs.begin(), kernel.outputs.end(), [&](const KernelOutput& out) { return out.name == n; }))
      throw UsageError("--outputs names '" + n + "', which is not an output of the script (its outputs: " + known + ")");
  std::erase_if(kernel.outputs, [&](const KernelOutput& out) {
    return std::find(names.begin(), names.end(), out.name) == names.end();
  });
}

double parse_number(const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw UsageError("bad number '" + text + "' in " + what);
  }
}

Options parse_args(int argc, char** argv) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  auto value = [&](size_t& i, const std::string& flag) -> std::string {
    if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
    return args[++i];
  };
  auto add_eval_input = [&](const std::string& v) {
    auto eq = v.find('=');
    std::string name = v.substr(0, eq);
    if (name.empty()) throw UsageError("--eval expects NAME=VALUE, got '" + v + "'");
    std::vector<double> vals;
    std::stringstream ss(v.substr(eq + 1));
    std::string item;
    while (std::getline(ss, item, ',')) vals.push_back(parse_number(item, v));
    if (vals.empty()) throw UsageError("--eval: no value in '" + v + "'");
    o.eval_inputs[name] = vals;
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    try {
      if (a == "--help" || a == "-h") {
        std::cout << kUsage;
        std::exit(0);
      } else if (a == "--passes") {  // the pass table (gen/opt/pipeline.cpp), one pass per line
        size_t width = 0;
        for (const auto& p : opt::pass_table()) width = std::max(width, p.name.size());
        for (const auto& p : opt::pass_table())
          std::cout << p.name << std::string(width + 2 - p.name.size(), ' ') << p.description << "\n";
        std::exit(0);
      } else if (a == "--version") {
        std::cout << "cgagen " << CGAGEN_VERSION << "\n";
        std::exit(0);
      } else if (a == "--target") {
        std::string t = value(i, a);
        if (t == "list") {  // the table of targets (gen/emit/targets.cpp), one name per line; -v: details
          const bool verbose = i + 1 < args.size() && args[i + 1] == "-v";
          for (const auto& s : emit::targets()) {
            std::cout << s.name;
            if (verbose) {
              std::cout << std::string(s.name.size() < 11 ? 11 - s.name.size() : 1, ' ') << s.extension
                        << std::string(s.extension.size() < 6 ? 6 - s.extension.size() : 1, ' ') << s.summary
                        << "; checked with " << s.toolchain;
            }
            std::cout << "\n";
          }
          std::exit(0);
        }
        o.emit.target = emit::parse_target(t);
        o.target_given = true;
      } else if (a == "--target-extension") {  // for build systems: the file extension of a target
        std::cout << emit::syntax(value(i, a)).extension << "\n";
        std::exit(0);
      } else if (a == "-O0" || a == "-O1" || a == "-O2") {
        o.level = opt::parse_level(a);
      } else if (a == "-o") {
        o.output = value(i, a);
      } else if (a == "--name") {
        o.name = value(i, a);
        if (!emit::is_identifier(o.name))
          throw UsageError("--name '" + o.name + "' is not a name: use letters, digits and _, not starting with a digit");
      } else if (a == "--templates") {
        o.emit.template_dir = value(i, a);
      } else if (a == "--pack") {
        std::string v = value(i, a);
        auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0) throw UsageError("--pack expects NAME=KIND, got '" + v + "'");
        o.emit.pack[v.substr(0, eq)] = emit::parse_pack(v.substr(eq + 1));
      } else if (a == "--return") {
        o.emit.return_output = value(i, a);
      } else if (a == "--algebra") {
        o.algebra = value(i, a);
        o.algebra_given = true;
      } else if (a == "--outputs") {
        std::stringstream ss(value(i, a));
        for (std::string item; std::getline(ss, item, ',');)
          if (!item.empty()) o.outputs.push_back(item);
        if (o.outputs.empty()) throw UsageError("--outputs names no output");
      } else if (a == "--jacobian") {
        std::stringstream ss(value(i, a));
        for (std::string item; std::getline(ss, item, ',');)
          if (!item.empty()) o.jacobian.push_back(item);
        if (o.jacobian.empty()) throw UsageError("--jacobian names no input");
      } else if (a == "--uniform") {
        std::stringstream ss(value(i, a));
        std::string item;
        while (std::getline(ss, item, ','))
          if (!item.empty()) o.uniforms.push_back(item);
      } else if (a == "--stage-at") {
        std::stringstream ss(value(i, a));
        for (std::string item; std::getline(ss, item, ',');)
          if (!item.empty()) o.stage_at.push_back(item);
        if (o.stage_at.empty()) throw UsageError("--stage-at names no value");
      } else if (a == "--gpc") {
        o.gpc = true;
      } else if (a == "--library") {
        o.library = true;
      } else if (a == "--also") {
        const std::string v = value(i, a);
        const auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
          throw UsageError("--also expects TARGET=FILE, got '" + v + "'");
        o.also.emplace_back(emit::parse_target(v.substr(0, eq)), v.substr(eq + 1));
      } else if (a == "--type") {
        o.type = value(i, a);
        bool ok = !o.type.empty();
        for (size_t k = 0; k < o.type.size(); ++k) {
          const char c = o.type[k];
          ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (c == ':' || c == ' '));
        }
        if (!ok) throw UsageError("--type '" + o.type + "' is not a C type name");
      } else if (a == "--stats") {
        o.stats = true;
      } else if (a == "--stats-out") {
        o.stats_out = value(i, a);
      } else if (a == "--diff") {
        opt::Level x = opt::parse_level(value(i, a));
        opt::Level y = opt::parse_level(value(i, a));
        o.diff = {x, y};
      } else if (a == "--dump-ast") {
        o.dump_ast = true;
      } else if (a == "--Werror") {
        o.werror = true;
      } else if (a == "--eval") {
        o.eval = true;
        while (i + 1 < args.size() && args[i + 1].find('=') != std::string::npos && args[i + 1][0] != '-')
          add_eval_input(args[++i]);
      } else if (o.eval && a.find('=') != std::string::npos && a[0] != '-') {
        add_eval_input(a);  // `--eval SCRIPT x=1 y=2`: the values may follow the script
      } else if (!a.empty() && a[0] == '-' && a != "-") {
        throw UsageError("unknown option '" + a + "'");
      } else {
        if (!o.script.empty()) throw UsageError("more than one script given ('" + o.script + "' and '" + a + "')");
        o.script = a;
      }
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  if (o.script.empty()) throw UsageError("no script given");
  if (!o.stage_at.empty() && (!o.uniforms.empty() || !o.jacobian.empty()))
    throw UsageError("--stage-at excludes --uniform and --jacobian");
  int modes = o.stats + o.diff.has_value() + o.dump_ast + o.eval;
  if (modes > 1) throw UsageError("--stats, --diff, --dump-ast and --eval exclude each other");
  if (o.gpc && o.library) throw UsageError("--gpc and --library exclude each other");
  if (!o.also.empty() && !o.library) throw UsageError("--also applies to --library");
  if (o.gpc) {
    if (modes || !o.uniforms.empty() || !o.stage_at.empty() || !o.outputs.empty() || !o.jacobian.empty() || !o.name.empty() || !o.stats_out.empty() || !o.emit.pack.empty() ||
        !o.emit.return_output.empty())
      throw UsageError("--gpc takes --algebra, -O, -o, --Werror, --target, --type and --templates only");
    bool known = !o.target_given;
    for (const auto& t : emit::statement_targets()) known = known || t == o.emit.target.name;
    if (!known)
      throw UsageError(std::string("--gpc prints C, C++, CUDA or OpenCL statements: --target cpp, cuda or opencl, not ") +
                       o.emit.target.name);
  } else if (o.library) {
    if (o.diff || o.dump_ast || o.eval || !o.uniforms.empty() || !o.stage_at.empty() || !o.outputs.empty() || !o.jacobian.empty() || !o.name.empty() ||
        !o.stats_out.empty() || !o.emit.pack.empty() || !o.emit.return_output.empty() || o.algebra_given || !o.type.empty())
      throw UsageError("--library takes -O, -o, --target, --templates, --also and --stats only (the spec names the algebra)");
    if (o.stats && !o.also.empty()) throw UsageError("--also writes code: not with --stats");
  } else if (!o.type.empty()) {
    throw UsageError("--type applies to --gpc");
  }
  return o;
}

// --dump-ast: an indented S-expression view of the script.
const char* binary_name(front::BinaryOp op) {
  switch (op) {
    case front::BinaryOp::Add: return "+";
    case front::BinaryOp::Sub: return "-";
    case front::BinaryOp::Geo: return "*";
    case front::BinaryOp::Div: return "/";
    case front::BinaryOp::Inner: return ".";
    case front::BinaryOp::Outer: return "^";
  }
  return "?";
}

std::string dump_expr(const front::ExprPtr& e) {
  if (!e) return "<none>";
  using K = front::Expr::Kind;
  switch (e->kind) {
    case K::Number: return e->text;
    case K::Name: return e->text;
    case K::MacroArg: return "_P(" + std::to_string(e->index) + ")";
    case K::Unary: {
      const char* op = e->unary_op == front::UnaryOp::Negate ? "neg" : e->unary_op == front::UnaryOp::Reverse ? "~" : "dual";
      return std::string("(") + op + " " + dump_expr(e->args.at(0)) + ")";
    }
    case K::Binary:
      return std::string("(") + binary_name(e->binary_op) + " " + dump_expr(e->args.at(0)) + " " +
             dump_expr(e->args.at(1)) + ")";
    case K::Compare:
    case K::Logic: {
      std::string s = "(" + e->text;
      for (const auto& a : e->args) s += " " + dump_expr(a);
      return s + ")";
    }
    case K::Call: {
      std::string s = "(call " + e->text;
      for (const auto& a : e->args) s += " " + dump_expr(a);
      return s + ")";
    }
  }
  return "?";
}

void dump_stmt(const front::Stmt& s, std::string& out, const std::string& indent) {
  std::string where = std::to_string(s.loc.line) + ":" + std::to_string(s.loc.col);
  switch (s.kind) {
    case front::Stmt::Kind::Assign: {
      const char* m = s.marker == front::Marker::Output ? "?" : s.marker == front::Marker::Visual ? ":"
                      : s.marker == front::Marker::EvalOnly ? "!" : "";
      out += indent + where + " assign " + m + s.name + " = " + dump_expr(s.value) + "\n";
      break;
    }
    case front::Stmt::Kind::MacroDef:
      out += indent + where + " macro " + s.name + "\n";
      for (const auto& b : s.body) dump_stmt(*b, out, indent + "  ");
      out += indent + "  result " + dump_expr(s.result) + "\n";
      break;
    case front::Stmt::Kind::Pragma: {
      out += indent + where + " pragma";
      for (const auto& w : s.words) out += " " + w;
      out += "\n";
      break;
    }
    case front::Stmt::Kind::ExprStmt:
      out += indent + where + " expr " + dump_expr(s.value) + "\n";
      break;
    case front::Stmt::Kind::If:
      out += indent + where + " if " + dump_expr(s.value) + "\n";
      for (const auto& b : s.body) dump_stmt(*b, out, indent + "  ");
      if (s.else_loc.line > 0) {
        out += indent + std::to_string(s.else_loc.line) + ":" + std::to_string(s.else_loc.col) + " else\n";
        for (const auto& b : s.else_body) dump_stmt(*b, out, indent + "  ");
      }
      break;
  }
}

void write_text(const std::string& path, const std::string& text) {
  if (path.empty() || path == "-") {
    std::cout << text;
    std::cout.flush();
    return;
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << text;
  if (!out) throw std::runtime_error("error while writing " + path);
}

// SCRIPT "-": the script from standard input, named <stdin> in diagnostics.
front::SourceFile load_script(const std::string& path) {
  if (path != "-") return front::SourceFile::load(path);
  std::ostringstream text;
  text << std::cin.rdbuf();
  front::SourceFile file("<stdin>", text.str());
  file.check();
  return file;
}

// A kernel with uniform inputs, or split at named values: the staged form (opt/stage.hpp) in every mode.
int run_staged(const Options& o, const Kernel& kernel, const emit::EmitOptions& eo,
               const std::vector<std::string>& uniforms, const std::string& name) {
  auto staged_of = [&](opt::Level level) {
    try {
      return o.stage_at.empty() ? opt::stage(opt::optimize(kernel, level), uniforms)
                                : opt::stage_at(kernel, o.stage_at, level);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  };
  auto code_of = [&](const opt::StagedProgram& s) { return emit::emit({&s.prepare, &s.body}, eo); };
  if (o.diff) {
    opt::Program a = opt::optimize(kernel, o.diff->first);
    opt::StagedProgram b = staged_of(o.diff->second);
    std::string la = "-O" + std::to_string(static_cast<int>(a.level));
    std::string lb = "-O" + std::to_string(static_cast<int>(b.body.level));
    std::string d = opt::unified_diff(emit::emit(a, eo), code_of(b), name + " " + la, name + " " + lb + " staged");
    write_text(o.output, (d.empty() ? "(no difference in the code)\n" : d) + "unstaged " + la + ":\n" +
                             opt::format_stats(a) + "staged " + lb + ":\n" + opt::format_staged_stats(b));
    return 0;
  }
  opt::Program program = opt::optimize(kernel, o.level);
  opt::StagedProgram staged = staged_of(o.level);
  if (o.eval) {
    std::vector<opt::EvalLine> plain, split;
    try {
      plain = opt::evaluate(program, o.eval_inputs);
      split = opt::evaluate_staged(staged, o.eval_inputs);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    write_text(o.output, opt::format_eval(split));
    const opt::StagedCheck check = opt::compare_staged(split, plain);
    if (!check.ok) {
      std::cerr << "cgagen: error: the staged kernel (prepare then body) differs from the unstaged kernel by "
                << check.max_rel_error << " (relative); please report the script\n";
      return 1;
    }
    return 0;
  }
  if (o.stats) {
    write_text(o.output, opt::format_staged_stats(staged) + opt::format_inputs(program));
    return 0;
  }
  std::string code = code_of(staged);
  if (!o.stats_out.empty()) write_text(o.stats_out, opt::format_staged_stats(staged));
  write_text(o.output, code);
  return 0;
}

// --gpc: the source with its GPC blocks compiled (gen/gpc/gpc.hpp); warnings and errors located in it.
int run_gpc(const Options& o, const front::SourceFile& file) {
  gpc::Options go;
  go.level = o.level;
  go.target = o.emit.target;
  if (!o.type.empty()) go.type = o.type;
  try {
    gpc::Result r = gpc::rewrite(file, go);
    for (const auto& w : r.warnings)
      std::cerr << front::format_diagnostic(file, w.loc, w.message + (o.werror ? " [-Werror]" : ""),
                                            o.werror ? "error" : "warning");
    if (o.werror && !r.warnings.empty()) return 1;
    write_text(o.output, r.text);
    return 0;
  } catch (const front::CompileError& e) {
    std::cerr << front::format_diagnostic(file, e.loc(), e.what());
    return 1;
  }
}

// --library: the spec's library in the target, or one op-count line per function (--stats).
int run_library(const Options& o) {
  std::optional<front::SourceFile> loaded;
  try {
    loaded.emplace(load_script(o.script));
  } catch (const front::FileError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  const front::SourceFile& file = *loaded;
  try {
    const library::Spec spec =
        library::parse_spec(file, o.script == "-" ? "" : std::filesystem::path(o.script).parent_path().string());
    const library::Library lib = library::build(spec, o.level);
    if (o.stats) {
      std::string out;
      for (const auto& f : lib.functions) {
        out += std::string(f.op->name) + "(" + lib.types[f.a].name + (f.op->arity == 2 ? ", " + lib.types[f.b].name : "") +
               ") -> " + lib.types[f.result].name + ": " + opt::format_counts(opt::program_stats(f.program).total) + "\n";
      }
      for (const auto& m : lib.matrices)
        out += "matrix(" + lib.types[m.a].name + ", " + lib.types[m.b].name + ") -> " + lib.types[m.result].name + ": " +
               opt::format_counts(opt::program_stats(m.program).total) + "\n";
      for (const auto& sk : lib.skipped)
        out += std::string(sk.op->name) + "(" + lib.types[sk.a].name + (sk.op->arity == 2 ? ", " + lib.types[sk.b].name : "") +
               "): not generated: " + sk.reason + "\n";
      write_text(o.output, out);
      return 0;
    }
    emit::EmitOptions eo = o.emit;
    eo.script_name = std::filesystem::path(o.script).filename().string();
    write_text(o.output, library::emit_library(lib, eo, eo.script_name));
    for (const auto& [target, file] : o.also) {
      eo.target = target;
      write_text(file, library::emit_library(lib, eo, eo.script_name));
    }
    return 0;
  } catch (const front::CompileError& e) {
    std::cerr << front::format_diagnostic(file, e.loc(), e.what());
    return 1;
  }
}

int run(const Options& o) {
  if (o.library) return run_library(o);
  try {
    algebra::use(algebra::load(o.algebra));
  } catch (const algebra::AlgebraError& e) {  // "file:line: error: ..." for a bad definition file
    const std::string m = e.what();
    std::cerr << (m.find(": error: ") != std::string::npos ? "" : "cgagen: error: ") << m << "\n";
    return 1;
  }
  std::optional<front::SourceFile> loaded;
  try {
    loaded.emplace(load_script(o.script));
  } catch (const front::FileError& e) {  // a directory, a binary file, an over-long line: one located line
    std::cerr << e.what() << "\n";
    return 1;
  }
  const front::SourceFile& file = *loaded;
  if (o.gpc) return run_gpc(o, file);
  const bool from_stdin = o.script == "-";
  try {
    symbolic::NodeCacheScope caches;  // shared by the expander and every optimization of this script
    front::Script script = front::parse(file);
    const std::string dir = from_stdin ? "" : std::filesystem::path(o.script).parent_path().string();
    if (auto sa = expand_algebra_pragma::script_algebra(script, dir)) {
      if (o.algebra_given &&
          expand_algebra_pragma::algebra_name(o.algebra) != expand_algebra_pragma::algebra_name(sa->spelling))
        throw front::CompileError(sa->loc, "'#pragma algebra " + sa->spelling + "' conflicts with --algebra " + o.algebra);
      algebra::use(sa->algebra);
    }
    if (o.dump_ast) {
      std::string out;
      for (const auto& s : script.statements) dump_stmt(*s, out, "");
      write_text(o.output, out);
      return 0;
    }
    std::string name = !o.name.empty() ? o.name : from_stdin ? "kernel"
                                                       : emit::c_identifier(std::filesystem::path(o.script).stem().string());
    Kernel kernel = expand(script, name, nullptr, o.jacobian);
    for (const auto& w : kernel.warnings)
      std::cerr << front::format_diagnostic(file, w.loc, w.message + (o.werror ? " [-Werror]" : ""),
                                            o.werror ? "error" : "warning");
    if (o.werror && !kernel.warnings.empty()) return 1;
    if (!o.outputs.empty()) keep_outputs(kernel, o.outputs);
    emit::EmitOptions eo = o.emit;
    eo.script_name = from_stdin ? "<stdin>" : std::filesystem::path(o.script).filename().string();
    std::vector<std::string> uniforms;
    try {
      uniforms = opt::uniform_inputs(kernel, o.uniforms);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    if (!uniforms.empty() || !o.stage_at.empty()) return run_staged(o, kernel, eo, uniforms, name);
    if (o.diff) {
      opt::Program a = opt::optimize(kernel, o.diff->first);
      opt::Program b = opt::optimize(kernel, o.diff->second);
      std::string la = "-O" + std::to_string(static_cast<int>(a.level));
      std::string lb = "-O" + std::to_string(static_cast<int>(b.level));
      std::string d = opt::unified_diff(emit::emit(a, eo), emit::emit(b, eo), name + " " + la, name + " " + lb);
      write_text(o.output,
                 (d.empty() ? "(no difference in the code)\n" : d) + opt::stats_delta(a, b) + opt::format_products(kernel));
      return 0;
    }
    opt::Program program = opt::optimize(kernel, o.level);
    if (o.eval) {
      try {
        write_text(o.output, opt::format_eval(opt::evaluate(program, o.eval_inputs)));
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      return 0;
    }
    if (o.stats) {
      write_text(o.output, opt::format_stats(program) + opt::format_passes(program) + opt::format_products(kernel) +
                               opt::format_inputs(program));
      return 0;
    }
    std::string code = emit::emit(program, eo);
    if (!o.stats_out.empty()) write_text(o.stats_out, opt::format_stats(program));
    write_text(o.output, code);
    return 0;
  } catch (const front::CompileError& e) {
    std::cerr << front::format_diagnostic(file, e.loc(), e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o = parse_args(argc, argv);
    return run(o);
  } catch (const UsageError& e) {
    std::cerr << "cgagen: " << e.what() << "\n(run cgagen --help for the options)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cgagen: error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "cgagen: error: unknown failure\n";
    return 1;
  }
}
