// The statement emitter (statements.hpp): a Program as statements of a C-family function body.
#include "emit/statements.hpp"

#include <stdexcept>

#include "emit/printer.hpp"
#include "opt/order.hpp"

namespace cgagen::emit {

const std::vector<std::string>& statement_targets() {
  static const std::vector<std::string> names{"cpp", "cuda", "opencl"};
  return names;
}

std::string emit_statements(const opt::Program& program, const StatementOptions& options) {
  bool known = false;
  for (const auto& t : statement_targets()) known |= t == options.target.name;
  if (!known)
    throw std::invalid_argument(std::string("gpc blocks are printed as C, C++, CUDA or OpenCL statements (--target ") +
                                "cpp, cuda or opencl), not as " + options.target.name);
  algebra::Using use(program.algebra);
  const Syntax& sx = options.target.syntax();
  const Precision prec{options.type, options.type == "float", "", "", ""};

  opt::SymbolNames canon = opt::symbol_names(program);
  opt::CanonicalKeys keys(canon);
  opt::SymbolNames code;
  for (const auto& input : program.inputs) {
    if (!input.is_multivector) {
      code[input.symbols.at(0)] = input.name;
      continue;
    }
    auto it = options.elements.find(input.name);
    for (size_t k = 0; k < input.symbols.size(); ++k)
      code[input.symbols[k]] = it != options.elements.end() && k < it->second.size()
                                   ? it->second[k]
                                   : fill_pattern(sx.element, {{"name", input.name}, {"k", std::to_string(k)}});
  }
  for (const auto& t : program.temps) code[t.sym] = options.temp_prefix + t.name;

  Printer pr(options.target, prec, code, keys);
  const std::string& T = options.type;
  std::string out;
  int counted = 0;  // the number the compiler gives the next line after a `#line` (0: none written yet)
  auto line = [&](const std::vector<int>& lines, size_t i) {
    const int n = i < lines.size() ? lines[i] : 0;
    if (!options.line_file.empty() && n > 0 && n != counted) {
      out += "#line " + std::to_string(n) + " " + options.line_file + "\n";
      counted = n;
    }
    if (counted > 0) ++counted;  // the statement's own line
  };
  for (size_t i = 0; i < program.outputs.size(); ++i) {
    const auto& o = program.outputs[i];
    const size_t n = o.slots.size();
    if (n > 0) line(options.output_lines, i);
    if (n == 1) out += options.indent + T + " " + o.name + ";\n";
    else if (n > 1) out += options.indent + T + " " + o.name + "[" + std::to_string(n) + "];\n";
  }
  const bool scope = !program.temps.empty();
  const std::string in = options.indent + (scope ? sx.indent : "");
  if (scope) {
    out += options.indent + "{\n";
    if (counted > 0) ++counted;
  }
  for (const opt::Assignment& a : opt::print_order(program)) {
    if (a.kind == opt::Assignment::Kind::Temp) {
      const auto& t = program.temps[a.index];
      line(options.temp_lines, a.index);
      out += in + fill_pattern(sx.temp, {{"T", T}, {"name", options.temp_prefix + t.name}, {"value", pr.print(t.value)}}) +
             "\n";
      continue;
    }
    const auto& o = program.outputs[a.index];
    const size_t n = o.slots.size(), k = a.slot;
    line(a.index < options.slot_lines.size() ? options.slot_lines[a.index] : std::vector<int>{}, k);
    const std::string elem = n == 1 ? o.name : fill_pattern(sx.element, {{"name", o.name}, {"k", std::to_string(k)}});
    out += in + fill_pattern(sx.assign, {{"elem", elem},
                                         {"value", pr.print(o.slots[k].value)},
                                         {"blade", algebra::blade_name(o.slots[k].blade)},
                                         {"c", sx.comment}}) +
           "\n";
  }
  // The code after a block may read only some outputs (an IK chain's intermediate joints): no
  // -Wunused-but-set-variable for the others.
  std::string uses;
  for (const auto& o : program.outputs)
    if (!o.slots.empty())
      uses += (uses.empty() ? "" : " ") + fill_pattern(sx.unused.empty() ? "(void)${name};" : sx.unused, {{"name", o.name}});
  if (!uses.empty()) out += in + uses + "\n";
  if (scope) out += options.indent + "}\n";
  return out;
}

}  // namespace cgagen::emit
