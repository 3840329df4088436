// The emitter (see emit.hpp): one code path driven by the target's Syntax record (gen/emit/targets.cpp); GLSL packing
// and the dot dataflow graph are the only target-specific branches. Expressions are printed by lower/lower.hpp's rules.
#include "emit/emit.hpp"
#include "emit/batch.hpp"
#include "emit/names.hpp"
#include "emit/printer.hpp"
#include "opt/order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "symbolic/select.hpp"

#ifndef CGAGEN_TEMPLATE_DIR
#define CGAGEN_TEMPLATE_DIR "templates"
#endif

namespace cgagen::emit {

using namespace GiNaC;
using opt::CanonicalKeys;

const Target Target::Cpp{"cpp"};
const Target Target::Glsl{"glsl"};
const Target Target::Cuda{"cuda"};

Target parse_target(const std::string& t) { return Target{syntax(t).name.c_str()}; }

std::string file_extension(Target t) { return t.syntax().extension; }

std::string fill_pattern(const std::string& p, const std::map<std::string, std::string>& values) {
  std::string out;
  size_t pos = 0;
  while (true) {
    size_t open = p.find("${", pos);
    if (open == std::string::npos) break;
    size_t close = p.find('}', open + 2);
    if (close == std::string::npos) throw std::logic_error("cgagen pattern: unterminated ${ in " + p);
    auto it = values.find(p.substr(open + 2, close - open - 2));
    if (it == values.end()) throw std::logic_error("cgagen pattern: unknown key in " + p);
    out.append(p, pos, open - pos);
    out += it->second;
    pos = close + 1;
  }
  out.append(p, pos, std::string::npos);
  return out;
}

const Packing& packing(Pack p) {
  static const Packing rows[] = {
      {Pack::Array, "float", SIZE_MAX, Packing::Param::Array, "", false, false, ""},
      {Pack::Mat3x4, "mat3x4", 12, Packing::Param::Typed, "${name}[${row}][${col}]", true, false, ""},
      {Pack::Vec4, "vec4", 4, Packing::Param::Typed, "${name}[${k}]", true, false, ""},
      {Pack::Vec3, "vec3", 3, Packing::Param::Typed, "${name}[${k}]", true, false, ""},
      {Pack::Float, "float", 1, Packing::Param::Typed, "${name}", false, false, ""},
      {Pack::Block, "block", SIZE_MAX, Packing::Param::None, "${store}[${row}][${col}]", false, true,
       "layout(std140) uniform ${store}_block {\n  vec4 ${store}[${rows}];  // value k at [k / 4][k % 4]\n};\n\n"},
      {Pack::Buffer, "buffer", SIZE_MAX, Packing::Param::Index, "${store}[prepared_index * ${K} + ${k}]", false, true,
       "layout(std430) readonly buffer ${store}_buffer {\n  float ${store}[];  // set i: values i * ${K} ... i * ${K} + "
       "${last}\n};\n\n"},
  };
  for (const Packing& row : rows)
    if (row.kind == p) return row;
  throw std::logic_error("packing: no row");
}

Pack parse_pack(const std::string& t) {
  for (Pack p : {Pack::Mat3x4, Pack::Vec4, Pack::Vec3, Pack::Float, Pack::Block, Pack::Buffer})
    if (t == packing(p).name) return p;
  throw std::invalid_argument("unknown packing '" + t + "' (expected mat3x4, vec4, vec3, float, block or buffer)");
}

// An installed cgagen (BINDIR/cgagen) finds its templates in BINDIR/../share/cgagen/templates, wherever the
// prefix was moved; a cgagen run from the build tree, where that folder does not exist, uses the source tree's.
std::string default_template_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "cgagen" / "templates";
    if (std::filesystem::is_directory(installed, ec)) return installed.string();
  }
  return CGAGEN_TEMPLATE_DIR;
}

std::string fill_template(const std::string& text, const std::map<std::string, std::string>& values,
                          const std::string& template_name) {
  std::string out;
  size_t pos = 0;
  while (true) {
    size_t open = text.find("{{", pos);
    if (open == std::string::npos) break;
    size_t close = text.find("}}", open + 2);
    if (close == std::string::npos)
      throw std::runtime_error("template " + template_name + ": unterminated placeholder at offset " +
                               std::to_string(open));
    std::string key = text.substr(open + 2, close - open - 2);
    auto it = values.find(key);
    if (it == values.end())
      throw std::runtime_error("template " + template_name + ": unknown placeholder {{" + key + "}}");
    out.append(text, pos, open - pos);
    out += it->second;
    pos = close + 2;
  }
  out.append(text, pos, std::string::npos);
  return out;
}

namespace {

// The exact decimal form of p/q when q = 2^a 5^b, else empty.
std::string exact_decimal(const numeric& v) {
  numeric p = abs(v.numer()), q = v.denom();
  int twos = 0, fives = 0;
  numeric r = q;
  while (irem(r, 2).is_zero()) r = r / 2, ++twos;
  while (irem(r, 5).is_zero()) r = r / 5, ++fives;
  if (r != 1) return "";
  int k = std::max(twos, fives);
  numeric scaled = p * GiNaC::pow(numeric(10), numeric(k)) / q;  // an integer
  std::ostringstream os;
  os << scaled;
  std::string digits = os.str();
  if (k == 0) return digits + ".0";
  while (static_cast<int>(digits.size()) <= k) digits = "0" + digits;
  return digits.substr(0, digits.size() - k) + "." + digits.substr(digits.size() - k);
}

}  // namespace

std::string literal(const numeric& v, Target target, bool single) {
  const Syntax& sx = target.syntax();
  std::string suffix = single ? sx.single_suffix : sx.double_suffix;
  std::string sign = v.is_negative() ? "-" : "";
  if (!v.is_rational()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v.to_double());
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s + suffix;
  }
  std::string dec = exact_decimal(v);
  if (!dec.empty() && dec.size() <= 24) return sign + dec + suffix;
  numeric p = abs(v.numer()), q = v.denom();
  std::ostringstream os;
  os << sign << "(" << p << ".0" << suffix << " / " << q << ".0" << suffix << ")";
  return os.str();
}

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read template " + path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

struct Param {
  std::string name;
  bool multivector;
  size_t size;
  Pack pack;
};

std::string indent(const std::string& body) { return body; }

// The symbols the program's temporaries and outputs read (each shared node visited once; `kept` holds every
// visited node alive, since op() of a sum may build a fresh node whose address a freed one had).
std::set<GiNaC::ex, GiNaC::ex_is_less> read_symbols(const opt::Program& program) {
  std::set<GiNaC::ex, GiNaC::ex_is_less> out;
  std::set<const GiNaC::basic*> seen;
  std::vector<GiNaC::ex> todo, kept;
  for (const auto& t : program.temps) todo.push_back(t.value);
  for (const auto& o : program.outputs)
    for (const auto& slot : o.slots) todo.push_back(slot.value);
  while (!todo.empty()) {
    const GiNaC::ex e = todo.back();
    todo.pop_back();
    if (!seen.insert(&GiNaC::ex_to<GiNaC::basic>(e)).second) continue;
    kept.push_back(e);
    if (GiNaC::is_a<GiNaC::symbol>(e)) out.insert(e);
    for (size_t i = 0; i < e.nops(); ++i) todo.push_back(e.op(i));
  }
  return out;
}

// The local element k of a loaded input lives in (Syntax::load), before spelling: NAME_<blade ident>, or
// NAME_<k> where the blades repeat (a staged kernel's prepared values are all labelled as scalars).
std::string load_name(const KernelInput& in, size_t k) {
  std::set<algebra::BladeIndex> distinct(in.blades.begin(), in.blades.end());
  if (distinct.size() == in.blades.size()) return in.name + "_" + algebra::blade_ident(in.blades[k]);
  return in.name + "_" + std::to_string(k);
}

}  // namespace

namespace {

std::string as_text(const Syntax& sx, const std::string& s) { return sx.text ? sx.text(s) : s; }

// The dot target: the program's dataflow, one node per input blade, temporary and output blade, an edge
// from every symbol an expression reads.
template <class Label>
std::string dataflow(const opt::Program& program, const opt::SymbolNames& code, const Label& label) {
  std::string s;
  auto node = [](const std::string& id) { return "\"" + id + "\""; };
  for (const auto& in : program.inputs)
    for (size_t k = 0; k < in.symbols.size(); ++k)
      s += "  " + node(code.at(in.symbols[k])) + " [shape=box" +
           (in.is_multivector ? ", label=\"" + code.at(in.symbols[k]) + "\\n" + label(in.name, k, in.blades[k]) + "\"" : "") +
           "];\n";
  auto edges = [&](const GiNaC::ex& value, const std::string& to) {
    std::set<std::string> from;
    for (auto i = value.preorder_begin(); i != value.preorder_end(); ++i)
      if (is_a<symbol>(*i)) from.insert(code.at(*i));
    for (const auto& f : from) s += "  " + node(f) + " -> " + node(to) + ";\n";
  };
  for (const auto& t : program.temps) {
    s += "  " + node(t.name) + " [shape=ellipse];\n";
    edges(t.value, t.name);
  }
  for (const auto& o : program.outputs)
    for (size_t k = 0; k < o.slots.size(); ++k) {
      std::string id = o.name + "[" + std::to_string(k) + "]";
      s += "  " + node(id) + " [shape=doubleoctagon, label=\"" + id + "\\n" + label(o.name, k, o.slots[k].blade) +
           "\"];\n";
      edges(o.slots[k].value, id);
    }
  if (!s.empty()) s.pop_back();
  return s;
}

}  // namespace

std::string emit(const opt::Program& program, const EmitOptions& options) {
  return emit(std::vector<const opt::Program*>{&program}, options);
}

namespace {

// What every program of one file shares: the target's syntax, the options, the templates and the file's
// spelt names.
struct FileContext {
  Target target;
  const Syntax& sx;
  const EmitOptions& options;
  std::string file_tmpl_path, fn_tmpl_path, file_tmpl, fn_tmpl;
  std::string dispatch_tmpl_path, dispatch_tmpl;  // templates/NAME/dispatch.in, where the target has one
  std::map<std::string, std::string> spelt;

  // A name of the file as spelt for the target (emit/names.hpp).
  const std::string& id(const std::string& name) const { return spelt.at(name); }
  // The function's name (with a precision's suffix); LaTeX prints it as text.
  std::string fn_name(const std::string& name, const std::string& suffix = "") const {
    return sx.ident ? as_text(sx, name + suffix) : id(name) + suffix;
  }
  // Packing per parameter. Block and buffer are the body's way of reading a staged kernel's prepared values;
  // the prepare function's output of the same name stays an array (output = true).
  Pack pack_of(const std::string& name, size_t size, bool output = false) const {
    auto it = options.pack.find(name);
    Pack p = it == options.pack.end() ? Pack::Array : it->second;
    const Packing& pk = packing(p);
    if (pk.prepared_only) {
      if (name != "prepared")
        throw std::runtime_error("--pack " + name + "=" + pk.name +
                                 ": block and buffer apply to a staged kernel's prepared values only (--pack "
                                 "prepared=" + pk.name + " with --uniform or #pragma uniform)");
      if (output) return Pack::Array;
    }
    if (size > pk.capacity)
      throw std::runtime_error("cannot pack '" + name + "' (" + std::to_string(size) + " blades) as " + pk.name);
    return p;
  }
  // The packing of a parameter or output: --pack's for GLSL, arrays elsewhere.
  Pack param_pack(const std::string& name, size_t size, bool output = false) const {
    return sx.glsl_pack ? pack_of(name, size, output) : Pack::Array;
  }
};

// The templates of a target (the function template only for code targets; the file template only for the
// file's own target, not for a scalar twin).
FileContext load_file_context(const EmitOptions& options, Target target, bool file = true) {
  const Syntax& sx = target.syntax();
  const std::string dir = (options.template_dir.empty() ? default_template_dir() : options.template_dir) + "/" +
                          sx.name;
  FileContext f{target, sx, options, dir + "/file" + sx.extension + ".in", dir + "/function.in", "", "",
                dir + "/dispatch.in", "", {}};
  if (file) f.file_tmpl = read_file(f.file_tmpl_path);
  f.fn_tmpl = sx.kind == Syntax::Kind::Code ? read_file(f.fn_tmpl_path) : "";
  if (std::filesystem::exists(f.dispatch_tmpl_path)) f.dispatch_tmpl = read_file(f.dispatch_tmpl_path);
  return f;
}

// --pack and --return must name inputs or outputs of the programs, and apply to GLSL only.
void check_pack_and_return(const FileContext& f, const std::vector<const opt::Program*>& programs) {
  const EmitOptions& options = f.options;
  if (!f.sx.glsl_pack && (!options.pack.empty() || !options.return_output.empty()))
    throw std::runtime_error("--pack and --return apply to the glsl target only");
  for (const auto& [name, p] : options.pack) {
    bool found = false;
    for (const opt::Program* pr : programs) {
      for (const auto& in : pr->inputs) found |= in.name == name;
      for (const auto& o : pr->outputs) found |= o.name == name;
    }
    if (!found) throw std::runtime_error("--pack names '" + name + "', which is neither an input nor an output");
    f.pack_of(name, 0);  // block / buffer on anything but the prepared values is an error
  }
  if (!options.return_output.empty()) {
    bool found = false;
    for (const opt::Program* pr : programs)
      for (const auto& o : pr->outputs) found |= o.name == options.return_output;
    if (!found) throw std::runtime_error("--return names '" + options.return_output + "', which is not an output");
  }
}

// Every name of the file spelt once (emit/names.hpp), so that a prepare function and its body agree and a
// changed name cannot meet another.
std::map<std::string, std::string> spell_file_names(const Syntax& sx, const std::vector<const opt::Program*>& programs) {
  std::set<std::string> raw_names;
  // The locals of loaded inputs, where this target or its scalar twin (which prints with these names) loads.
  const bool loads = !sx.load.empty() || (!sx.scalar_twin.empty() && !syntax(sx.scalar_twin).load.empty());
  for (const opt::Program* pr : programs) {
    raw_names.insert(pr->name);
    for (const auto& in : pr->inputs) {
      raw_names.insert(in.name);
      if (loads && in.is_multivector)
        for (size_t k = 0; k < in.blades.size(); ++k) raw_names.insert(load_name(in, k));
    }
    for (const auto& o : pr->outputs) raw_names.insert(o.name);
    for (const auto& t : pr->temps) raw_names.insert(t.name);
  }
  return spellings(sx, raw_names);
}

// One program within its file: labels, the code names of its symbols and how its elements are addressed.
class ProgramEmitter {
 public:
  ProgramEmitter(const FileContext& f, const opt::Program& program)
      : f_(f), sx_(f.sx), program_(program), canon_(opt::symbol_names(program)), keys_(canon_),
        prepared_store_(spell(sx_, f.id(program.name) + "_prepared")) {
    for (const auto& in : program.inputs)
      if (in.name == "prepared") prepared_k_ = in.symbols.size();
    name_symbols();
  }
  ProgramEmitter(const ProgramEmitter&) = delete;  // keys_ refers to canon_
  ProgramEmitter& operator=(const ProgramEmitter&) = delete;

  // The program's functions (one per precision, or the dataflow graph), blade lists and input comments.
  std::string functions() const {
    if (sx_.kind == Syntax::Kind::Dataflow)
      return dataflow(program_, code_, [this](const std::string& n, size_t k, algebra::BladeIndex b) {
        return label(n, k, b);
      });
    std::string out;
    for (size_t i = 0; i < sx_.precisions.size(); ++i) out += (i ? "\n" : "") + function_text(sx_.precisions[i]);
    return out;
  }
  std::string blade_lists() const;
  std::string inputs_doc() const;
  // templates/NAME/dispatch.in filled for this program ("" where the target has none).
  std::string dispatch() const {
    if (f_.dispatch_tmpl.empty()) return "";
    const BatchParts b = batch_parts(sx_, program_, [this](const std::string& n) { return f_.id(n); });
    return fill_template(f_.dispatch_tmpl,
                         {{"name", f_.fn_name(program_.name)}, {"batch_params", b.params}, {"batch_names", b.names}},
                         f_.dispatch_tmpl_path);
  }

 private:
  // The label of element k of input or output NAME: its blade, or the program's label for it (staging).
  std::string label(const std::string& name, size_t k, algebra::BladeIndex blade) const {
    auto it = program_.labels.find(name);
    return it != program_.labels.end() && k < it->second.size() ? it->second[k] : algebra::blade_name(blade);
  }
  // Blade k of a parameter or output, in the target's syntax (GLSL packing included).
  std::map<std::string, std::string> pack_fields(const std::string& name, size_t k) const {
    return std::map<std::string, std::string>{
        {"name", f_.id(name)},          {"k", std::to_string(k)},
        {"row", std::to_string(k / 4)}, {"col", std::to_string(k % 4)},
        {"store", prepared_store_},     {"K", std::to_string(prepared_k_)},
        {"rows", std::to_string((prepared_k_ + 3) / 4)}, {"last", std::to_string(prepared_k_ ? prepared_k_ - 1 : 0)}};
  }
  std::string elem(const std::string& name, size_t k, Pack p, bool output = false) const {
    const Packing& pk = packing(p);
    if (*pk.element) return fill_pattern(pk.element, pack_fields(name, k));
    const std::string& pattern = output && !sx_.out_element.empty() ? sx_.out_element : sx_.element;
    return fill_pattern(pattern, {{"name", f_.id(name)}, {"k", std::to_string(k)}});
  }
  // Code names of the symbols: inputs as parameters, elements or loaded locals; temporaries by their names.
  void name_symbols() {
    for (const auto& in : program_.inputs) {
      if (!in.is_multivector) {
        code_[in.symbols.at(0)] = f_.id(in.name);
        continue;
      }
      Pack p = f_.param_pack(in.name, in.symbols.size());
      for (size_t k = 0; k < in.symbols.size(); ++k)
        code_[in.symbols[k]] = sx_.load.empty() ? elem(in.name, k, p) : f_.id(load_name(in, k));
    }
    for (const auto& t : program_.temps) code_[t.sym] = f_.id(t.name);
  }

  // One function's text at one precision, and the parts it is made of.
  struct Signature {
    std::string params, return_type = "void", declarations, ret_line;
  };
  std::string line(const std::string& s) const { return sx_.indent + s + "\n"; }
  std::string input_params(const std::string& T, std::string& splat) const;
  Signature outputs_signature(const std::string& T, std::string params) const;
  std::string unused_inputs(const std::set<GiNaC::ex, GiNaC::ex_is_less>& read) const;
  std::string loads(const std::string& T, const std::set<GiNaC::ex, GiNaC::ex_is_less>& read) const;
  std::string assignments(Printer& pr, const std::string& T) const;
  std::string function_text(const Precision& prec) const;

  const FileContext& f_;
  const Syntax& sx_;
  const opt::Program& program_;
  opt::SymbolNames canon_;
  mutable CanonicalKeys keys_;  // its memo fills as the functions are printed
  // The block / buffer that holds the prepared values (Pack::Block, Pack::Buffer), named after the body.
  std::string prepared_store_;
  size_t prepared_k_ = 0;
  opt::SymbolNames code_;
};

void add_to_list(std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; }

// The input parameters (comma-separated) and, in `splat`, the inputs as a prologue spells them.
std::string ProgramEmitter::input_params(const std::string& T, std::string& splat) const {
  std::string params;
  for (const auto& in : program_.inputs) {
    std::map<std::string, std::string> v{{"T", T}, {"name", f_.id(in.name)}, {"n", std::to_string(in.symbols.size())}};
    add_to_list(splat, fill_pattern(in.is_multivector ? sx_.splat_mv : sx_.splat_scalar, v));
    if (!in.is_multivector) {
      add_to_list(params, fill_pattern(sx_.scalar_param, v));
      continue;
    }
    const Packing& pk = packing(f_.param_pack(in.name, in.symbols.size()));
    switch (pk.param) {
      case Packing::Param::None: break;  // read from the uniform block
      case Packing::Param::Index: add_to_list(params, "int prepared_index"); break;
      case Packing::Param::Array: add_to_list(params, fill_pattern(sx_.mv_param, v)); break;
      case Packing::Param::Typed: add_to_list(params, std::string("in ") + pk.name + " " + f_.id(in.name)); break;
    }
  }
  return params;
}

// How the outputs leave the function: out parameters (appended to params), locals returned as a tuple, or
// GLSL's --return output as the return value.
ProgramEmitter::Signature ProgramEmitter::outputs_signature(const std::string& T, std::string params) const {
  Signature sig;
  std::string items;
  for (const auto& o : program_.outputs) {
    const size_t n = o.slots.size();
    const Packing& pk = packing(f_.param_pack(o.name, n, true));
    const bool typed = pk.param == Packing::Param::Typed;
    std::map<std::string, std::string> v{{"T", T}, {"name", f_.id(o.name)}, {"n", std::to_string(n)}};
    if (sx_.out_param.empty()) {
      sig.declarations += line(fill_pattern(sx_.out_decl, v));
      add_to_list(items, fill_pattern(sx_.return_item, v));
    } else if (sx_.glsl_pack && o.name == f_.options.return_output) {
      std::string decl = typed ? std::string(pk.name) + " " + f_.id(o.name) : T + " " + f_.id(o.name) + "[" + std::to_string(n) + "]";
      sig.return_type = typed ? std::string(pk.name) : "float[" + std::to_string(n) + "]";
      sig.declarations += line(decl + ";");
      sig.ret_line = line("return " + f_.id(o.name) + ";");
    } else if (typed) {
      add_to_list(params, std::string("out ") + pk.name + " " + f_.id(o.name));
    } else {
      add_to_list(params, fill_pattern(sx_.out_param, v));
    }
  }
  if (!items.empty()) sig.ret_line = line(fill_pattern(sx_.return_stmt, {{"items", items}}));
  sig.params = std::move(params);
  return sig;
}

// The target's mark for each input the body never reads (Syntax::unused).
std::string ProgramEmitter::unused_inputs(const std::set<GiNaC::ex, GiNaC::ex_is_less>& read) const {
  std::string out;
  if (!sx_.unused.empty())
    for (const auto& in : program_.inputs)
      if (std::none_of(in.symbols.begin(), in.symbols.end(), [&](const GiNaC::ex& x) { return read.count(x) > 0; }))
        out += line(fill_pattern(sx_.unused, {{"name", f_.id(in.name)}}));
  return out;
}

// The multivector input elements the body reads, loaded into locals (Syntax::load).
std::string ProgramEmitter::loads(const std::string& T, const std::set<GiNaC::ex, GiNaC::ex_is_less>& read) const {
  std::string out;
  if (!sx_.load.empty())
    for (const auto& in : program_.inputs)
      if (in.is_multivector)
        for (size_t k = 0; k < in.symbols.size(); ++k)
          if (read.count(in.symbols[k]))
            out += line(fill_pattern(sx_.load, {{"T", T}, {"name", f_.id(load_name(in, k))},
                                                {"elem", elem(in.name, k, Pack::Array)}}));
  return out;
}

// The temporaries and the output elements in print order (opt/order.hpp: each element as soon as what it reads
// is computed), then GLSL's padding of packed outputs.
std::string ProgramEmitter::assignments(Printer& pr, const std::string& T) const {
  std::string out;
  for (const opt::Assignment& a : opt::print_order(program_)) {
    if (a.kind == opt::Assignment::Kind::Temp) {
      const auto& t = program_.temps[a.index];
      out += line(fill_pattern(sx_.temp, {{"T", T}, {"name", f_.id(t.name)}, {"value", pr.print(t.value)}}));
      continue;
    }
    const auto& o = program_.outputs[a.index];
    const size_t k = a.slot;
    out += line(fill_pattern(sx_.assign, {{"elem", elem(o.name, k, f_.param_pack(o.name, o.slots.size(), true), true)},
                                          {"value", pr.print(o.slots[k].value)},
                                          {"blade", as_text(sx_, label(o.name, k, o.slots[k].blade))},
                                          {"c", sx_.comment}}));
  }
  for (const auto& o : program_.outputs) {
    Pack p = f_.param_pack(o.name, o.slots.size(), true);
    for (size_t k = o.slots.size(); packing(p).pads && k < packing(p).capacity; ++k)
      out += line(elem(o.name, k, p, true) + " = 0.0;  // (padding)");
  }
  return out;
}

std::string ProgramEmitter::function_text(const Precision& prec) const {
  const std::string& T = prec.type;
  Printer pr(f_.target, prec, code_, keys_);
  std::string splat;
  const Signature sig = outputs_signature(T, input_params(T, splat));
  std::string body;
  if (!sx_.prologue.empty()) body += line(fill_pattern(sx_.prologue, {{"splat", splat}}));
  // The symbols the body reads, once: for the unused inputs and the loads.
  const auto read = sx_.unused.empty() && sx_.load.empty() ? std::set<GiNaC::ex, GiNaC::ex_is_less>{}
                                                            : read_symbols(program_);
  body += unused_inputs(read);
  body += sig.declarations;
  body += loads(T, read);
  body += assignments(pr, T);
  body += sig.ret_line;
  if (!body.empty() && body.back() == '\n') body.pop_back();
  // The declaration of the block / buffer the body reads its prepared values from.
  std::string store;
  if (sx_.glsl_pack && prepared_k_)
    store = fill_pattern(packing(f_.pack_of("prepared", prepared_k_)).declaration, pack_fields("prepared", 0));
  const BatchParts b = batch_parts(sx_, program_, [this](const std::string& n) { return f_.id(n); });
  return prec.before + store + fill_template(f_.fn_tmpl,
                                             {{"return_type", sig.return_type},
                                              {"name", f_.fn_name(program_.name, prec.fn_suffix)},
                                              {"params", sig.params},
                                              {"body", indent(body)},
                                              {"type", T},
                                              {"qualifiers", sx_.qualifiers},
                                              {"batch_params", b.params},
                                              {"batch_loads", b.loads},
                                              {"batch_args", b.args},
                                              {"batch_stores", b.stores},
                                              {"batch_names", b.names}},
                                             f_.fn_tmpl_path) +
         prec.after;
}

// One NAME_OUT_blades list per output, from the spelt names: distinct outputs give distinct lists.
std::string ProgramEmitter::blade_lists() const {
  std::string out;
  for (const auto& o : program_.outputs) {
    std::string list;
    for (size_t k = 0; k < o.slots.size(); ++k)
      list += std::string(k ? ", " : "") + sx_.blade_quote + as_text(sx_, label(o.name, k, o.slots[k].blade)) +
              sx_.blade_quote;
    out += fill_pattern(sx_.blade_list, {{"fn", f_.fn_name(program_.name)},
                                         {"out", f_.id(o.name)},
                                         {"n", std::to_string(o.slots.size())},
                                         {"list", list},
                                         {"c", sx_.comment}}) +
           "\n";
  }
  return out;
}

// One comment line per input, with a multivector's blades.
std::string ProgramEmitter::inputs_doc() const {
  std::string out;
  for (const auto& in : program_.inputs) {
    out += sx_.comment + " input " + in.name;
    if (in.is_multivector) {
      out += ":";
      for (size_t k = 0; k < in.blades.size(); ++k) out += " " + label(in.name, k, in.blades[k]);
    }
    out += "\n";
  }
  return out;
}

}  // namespace

std::string emit(const std::vector<const opt::Program*>& programs, const EmitOptions& options) {
  algebra::Using in(programs.empty() ? nullptr : programs.front()->algebra);
  FileContext f = load_file_context(options, options.target);
  check_pack_and_return(f, programs);
  f.spelt = spell_file_names(f.sx, programs);
  // A staged kernel's prepare functions in the scalar twin's syntax and templates, with this file's names.
  std::optional<FileContext> twin;
  if (!f.sx.scalar_twin.empty()) {
    twin.emplace(load_file_context(options, parse_target(f.sx.scalar_twin), false));
    twin->spelt = f.spelt;
  }

  std::string functions, scalar_functions, blade_lists, inputs_doc, dispatch;
  for (size_t i = 0; i < programs.size(); ++i) {
    const bool prepare = i + 1 < programs.size();
    const ProgramEmitter pe(prepare && twin ? *twin : f, *programs[i]);
    std::string& out = prepare && twin ? scalar_functions : functions;
    out += (out.empty() ? "" : "\n") + pe.functions();
    blade_lists += pe.blade_lists();
    inputs_doc += pe.inputs_doc();
    dispatch += pe.dispatch();
  }
  // The file is named after the last program (a staged kernel's body: the function a user calls per element).
  const opt::Program& program = *programs.back();
  if (!blade_lists.empty() && blade_lists.back() == '\n') blade_lists.pop_back();
  if (!inputs_doc.empty() && inputs_doc.back() == '\n') inputs_doc.pop_back();
  return fill_template(f.file_tmpl,
                       {{"script", as_text(f.sx, options.script_name)},
                        {"level", std::to_string(static_cast<int>(program.level))},
                        {"name", f.fn_name(program.name)},
                        {"inputs", inputs_doc},
                        {"blade_lists", blade_lists},
                        {"functions", functions},
                        {"scalar_functions", scalar_functions},
                        {"dispatch", dispatch}},
                       f.file_tmpl_path);
}

std::string emit_functions(const std::vector<const opt::Program*>& programs, const EmitOptions& options) {
  algebra::Using in(programs.empty() ? nullptr : programs.front()->algebra);
  FileContext f = load_file_context(options, options.target, false);
  f.spelt = spell_file_names(f.sx, programs);
  std::string functions;
  for (const opt::Program* p : programs) functions += (functions.empty() ? "" : "\n") + ProgramEmitter(f, *p).functions();
  return functions;
}

}  // namespace cgagen::emit
