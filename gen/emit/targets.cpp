// The table of targets: one Syntax record per language (see emit.hpp). The templates of a target live in
// templates/<name>/; its interface and how it is checked are in docs/generator.md and tests/targets.
#include <set>
#include <stdexcept>
#include <utility>

#include "emit/emit.hpp"
#include "emit/names.hpp"

namespace cgagen::emit {

namespace {

// LaTeX: identifiers in math mode (an underscore would start a subscript), names and blades in text.
std::string latex_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '_' || c == '&' || c == '%' || c == '#' || c == '$') out += std::string("\\") + c;
    else if (c == '^') out += "\\textasciicircum{}";
    else out += c;
  }
  return out;
}
std::string latex_ident(const std::string& s) {
  if (s.size() == 1 && s != "_") return s;  // a one-letter name in math italics; "_" would start a subscript
  return "\\mathit{" + latex_text(s) + "}";
}

Precision prec(std::string type, bool single, std::string suffix = "", std::string before = "",
               std::string after = "") {
  return Precision{std::move(type), single, std::move(suffix), std::move(before), std::move(after)};
}

Syntax c_family() {
  Syntax s;
  s.single_suffix = "f";
  s.scalar_param = "${T} ${name}";
  s.mv_param = "const ${T} ${name}[${n}]";
  s.out_param = "${T} ${name}[${n}]";
  s.temp = "const ${T} ${name} = ${value};";
  s.assign = "${elem} = ${value};  ${c} ${blade}";
  s.blade_list = "${c} ${out}: ${list}";
  s.blade_quote = "";
  return s;
}

std::vector<Syntax> make_targets() {
  std::vector<Syntax> t;

  Syntax cpp = c_family();
  cpp.name = "cpp";
  cpp.extension = ".hpp";
  cpp.summary = "C++17 header: inline float and double overloads, out arrays";
  cpp.precisions = {prec("float", true), prec("double", false)};
  cpp.math_prefix = "std::";
  cpp.qualifiers = "inline";
  cpp.blade_list = "inline constexpr std::array<std::string_view, ${n}> ${fn}_${out}_blades = {${list}};";
  // An input listed by `#pragma in2out` that no value reads (-Wunused-parameter in the includer's build).
  cpp.unused = "(void)${name};";
  cpp.load = "const ${T} ${name} = ${elem};";
  cpp.blade_quote = "\"";
  t.push_back(cpp);

  // Lane-wise C++ over Google Highway (templates/simd): the kernel takes and returns vectors of lanes, each
  // operation a lane operation, a select a masked blend, the math Highway's vector math (cgagen_NAME in the
  // file template); NAME_batch runs it over streams with run-time dispatch (docs/generator.md, "simd").
  Syntax simd = c_family();
  simd.name = "simd";
  simd.extension = ".simd.hpp";
  simd.summary = "C++ SIMD batch kernels (Google Highway): NAME over lanes, NAME_batch over n elements, dispatched";
  simd.precisions = {prec("V", true)};
  simd.call = "cgagen_${fn}(d, ${args})";
  simd.select = "hn::IfThenElse(${op}(${a}, ${b}), ${x}, ${y})";
  simd.compare_names = {{"<", "hn::Lt"}, {"<=", "hn::Le"}, {"==", "hn::Eq"}};
  simd.negate = "hn::Neg(${x})";
  simd.constant = "hn::Set(d, ${value})";
  simd.qualifiers = "HWY_INLINE";
  simd.blade_list = cpp.blade_list;
  simd.blade_quote = "\"";
  simd.unused = "(void)${name};";
  simd.batch_in = "const In& ${name}";
  simd.batch_out = "const Out& ${name}";
  simd.batch_load_scalar = "const V ${lanes} = cgagen_load(d, ${name}, i, cgagen_rows_cache);";
  simd.batch_load_mv = "V ${lanes}[${n}];\n  cgagen_load(d, ${name}, i, ${lanes}, cgagen_rows_cache);";
  simd.batch_out_decl = "V ${lanes}[${n}];";
  simd.batch_store = "cgagen_store(d, ${name}, i, ${lanes});";
  simd.scalar_twin = "cpp";
  t.push_back(simd);

  Syntax glsl = c_family();
  glsl.name = "glsl";
  glsl.extension = ".glsl";
  glsl.summary = "GLSL 3.30 functions (float), out parameters, --pack / --return";
  glsl.precisions = {prec("float", true)};
  glsl.single_suffix = "";
  glsl.math_names = {{"atan2", "atan"}};
  glsl.mv_param = "in ${T} ${name}[${n}]";
  glsl.out_param = "out ${T} ${name}[${n}]";
  glsl.temp = "${T} ${name} = ${value};";
  glsl.glsl_pack = true;
  t.push_back(glsl);

  // CUDA is the C++ record plus qualifiers (and C math names, which nvcc provides for float and double).
  Syntax cuda = cpp;
  cuda.name = "cuda";
  cuda.extension = ".cuh";
  cuda.summary = "CUDA header: the C++ functions as __host__ __device__ __forceinline__";
  cuda.math_prefix = "";
  cuda.math_names = {{"abs", "fabs"}};
  cuda.qualifiers = "__host__ __device__ __forceinline__";
  t.push_back(cuda);

  Syntax hlsl = c_family();
  hlsl.name = "hlsl";
  hlsl.extension = ".hlsl";
  hlsl.summary = "HLSL functions (float), in/out array parameters";
  hlsl.precisions = {prec("float", true)};
  hlsl.single_suffix = "";
  hlsl.mv_param = "in ${T} ${name}[${n}]";
  hlsl.out_param = "out ${T} ${name}[${n}]";
  hlsl.temp = "${T} ${name} = ${value};";
  t.push_back(hlsl);

  // GLSL ES 3.00 (WebGL 2): the GLSL record, its own templates (a precision statement), packing included.
  Syntax glsl_es = glsl;
  glsl_es.name = "glsl-es";
  glsl_es.extension = ".essl";
  glsl_es.summary = "GLSL ES 3.00 functions (WebGL 2; float, highp), out parameters, --pack / --return";
  t.push_back(glsl_es);

  // WGSL (WebGPU): f32 only, as WGSL has no f64. Inputs are arrays by value; outputs are pointers to
  // function-space arrays (WGSL has no out parameters), so an output's blade is (*name)[k]. Literals stay
  // unsuffixed (abstract floats, converted to f32 where used: WGSL rounds them, as GLSL does).
  Syntax wgsl;
  wgsl.name = "wgsl";
  wgsl.extension = ".wgsl";
  wgsl.summary = "WGSL functions (WebGPU; f32 only), array inputs, ptr<function, array> outputs";
  wgsl.precisions = {prec("f32", true)};
  wgsl.scalar_param = "${name}: ${T}";
  wgsl.mv_param = "${name}: array<${T}, ${n}>";
  wgsl.out_param = "${name}: ptr<function, array<${T}, ${n}>>";
  wgsl.out_element = "(*${name})[${k}]";
  wgsl.temp = "let ${name}: ${T} = ${value};";
  wgsl.assign = "${elem} = ${value};  ${c} ${blade}";
  wgsl.blade_list = "${c} ${out}: ${list}";  // WGSL has no strings: the blade lists are comments
  wgsl.blade_quote = "";
  wgsl.select = "select(${y}, ${x}, ${a} ${op} ${b})";  // WGSL: select(false value, true value, condition)
  t.push_back(wgsl);

  Syntax opencl = c_family();
  opencl.name = "opencl";
  opencl.extension = ".cl";
  opencl.summary = "OpenCL C functions NAME_f32 and NAME_f64 (with cl_khr_fp64), private arrays";
  opencl.precisions = {prec("float", true, "_f32"),
                       prec("double", false, "_f64", "#ifdef cl_khr_fp64\n", "\n#endif")};
  opencl.math_names = {{"abs", "fabs"}};
  t.push_back(opencl);

  Syntax py;
  py.name = "python";
  py.extension = ".py";
  py.summary = "Python/NumPy: NAME(*inputs) -> tuple of outputs (floats or broadcast arrays)";
  py.precisions = {prec("", false)};
  py.math_prefix = "_np.";
  py.math_names = {{"atan2", "arctan2"}, {"asin", "arcsin"}, {"acos", "arccos"}, {"atan", "arctan"},
                   {"pow", "power"}};
  py.select = "_np.where(${a} ${op} ${b}, ${x}, ${y})";  // element-wise: inputs may be broadcast arrays
  py.comment = "#";
  py.indent = "    ";
  py.scalar_param = "${name}";
  py.mv_param = "${name}";
  py.splat_mv = "*${name}";
  py.prologue = "_s = _shape(${splat})";
  py.temp = "${name} = ${value}";
  py.assign = "${elem} = ${value}  ${c} ${blade}";
  py.out_decl = "${name} = [0.0] * ${n}";
  py.return_item = "_out(${name}, _s)";
  py.return_stmt = "return (${items},)";
  py.blade_list = "${fn}_${out}_blades = (${list},)";
  t.push_back(py);

  Syntax js;
  js.name = "javascript";
  js.extension = ".mjs";
  js.summary = "JavaScript ES module: export function NAME(...inputs) -> array of outputs (numbers)";
  js.precisions = {prec("", false)};
  js.math_prefix = "Math.";
  js.scalar_param = "${name}";
  js.mv_param = "${name}";
  js.temp = "const ${name} = ${value};";
  js.assign = "${elem} = ${value};  ${c} ${blade}";
  js.out_decl = "const ${name} = new Array(${n});";
  js.return_stmt = "return [${items}];";
  js.blade_list = "export const ${fn}_${out}_blades = [${list}];";
  t.push_back(js);

  Syntax rust;
  rust.name = "rust";
  rust.extension = ".rs";
  rust.summary = "Rust module: pub fn NAME_f32 / NAME_f64 with &[T; N] inputs and &mut [T; N] outputs";
  rust.precisions = {prec("f32", true, "_f32"), prec("f64", false, "_f64")};
  rust.math_prefix = "${T}::";
  rust.math_names = {{"pow", "powf"}, {"log", "ln"}};  // Rust's log takes a base; ln is the natural one
  rust.select = "(if ${a} ${op} ${b} { ${x} } else { ${y} })";
  rust.select_bare = "if ${a} ${op} ${b} { ${x} } else { ${y} }";
  rust.unused = "let _ = ${name};";  // an input no value reads (rustc's unused_variables)
  rust.scalar_param = "${name}: ${T}";
  rust.mv_param = "${name}: &[${T}; ${n}]";
  rust.out_param = "${name}: &mut [${T}; ${n}]";
  rust.temp = "let ${name}: ${T} = ${value};";
  rust.assign = "${elem} = ${value};  ${c} ${blade}";
  rust.blade_list = "#[allow(non_upper_case_globals, dead_code)]\npub const ${fn}_${out}_blades: [&str; ${n}] = [${list}];";
  t.push_back(rust);

  Syntax tex;
  tex.name = "latex";
  tex.extension = ".tex";
  tex.summary = "LaTeX standalone document: the optimized program as equations";
  tex.precisions = {prec("", false)};
  tex.call = "\\operatorname{${fn}}(${args})";
  tex.math_names = {{"sqrt", "\\sqrt{${args}}"}};
  tex.mul = " \\cdot ";
  tex.select = "\\begin{cases} ${x} & \\text{if } ${a} ${op} ${b} \\\\ ${y} & \\text{otherwise} \\end{cases}";
  tex.compare_names = {{"<=", "\\le"}, {"==", "="}};
  tex.comment = "%";
  tex.indent = "";
  tex.scalar_param = "$${name}$";
  tex.mv_param = "$${name}$ (${n} blades)";
  tex.out_param = "$${name}$ (${n} blades)";
  tex.element = "${name}_{${k}}";
  tex.temp = "\\noindent$${name} = ${value}$\\par";
  tex.assign = "\\noindent$${elem} = ${value}$ \\hfill ${blade}\\par";
  tex.blade_list = "\\noindent $${out}$: ${list}\\par";
  tex.blade_quote = "";
  tex.ident = latex_ident;
  tex.text = latex_text;
  t.push_back(tex);

  Syntax dot;
  dot.name = "dot";
  dot.extension = ".dot";
  dot.summary = "Graphviz digraph of the optimized program's dataflow";
  dot.kind = Syntax::Kind::Dataflow;
  dot.blade_list = "${c} ${out}: ${list}";
  dot.blade_quote = "";
  t.push_back(dot);

  // Identifier rules (emit/names.hpp). C and C++ reserve "__" anywhere and "_X" at the start, GLSL "__"
  // and "gl_", WGSL "__" at the start (a run of underscores is spelt as one there too).
  std::vector<std::string> underscore_upper;
  for (char c = 'A'; c <= 'Z'; ++c) underscore_upper.push_back(std::string("_") + c);
  for (Syntax& x : t) {
    x.reserved = reserved_words(x.name);
    if (x.name == "cpp" || x.name == "cuda" || x.name == "opencl" || x.name == "hlsl" || x.name == "simd") {
      x.single_underscores = true;
      x.reserved_prefixes = underscore_upper;
      // simd: its lanes (lanes_NAME), vector math (cgagen_NAME) and Highway's macros.
      if (x.name == "simd") x.reserved_prefixes.insert(x.reserved_prefixes.end(), {"lanes_", "cgagen_", "HWY_"});
    } else if (x.name == "glsl" || x.name == "glsl-es") {
      x.single_underscores = true;
      x.reserved_prefixes = {"gl_", "webgl_", "_webgl_"};
    } else if (x.name == "wgsl") {
      x.single_underscores = true;
    }
  }
  const std::map<std::string, std::string> toolchains = {
      {"cpp", "g++ (tests/kernels, tests/targets)"},
      {"simd", "g++ with libhwy: every ISA of the machine; aarch64-linux-gnu-g++ under qemu-aarch64 (tests/targets)"},
      {"glsl", "glslangValidator, Mesa GL 4.5 (tests/gpu, tests/targets)"},
      {"cuda", "nvcc when found; g++ with the qualifiers defined away (tests/targets)"},
      {"hlsl", "glslangValidator -D -> SPIR-V -> spirv-cross -> Mesa GL"},
      {"glsl-es", "glslangValidator, Chromium WebGL 2 (SwiftShader)"},
      {"wgsl", "Chromium WebGPU (Tint, SwiftShader)"},
      {"opencl", "PoCL (CPU) through the ICD loader"},
      {"python", "python3 with NumPy"},
      {"javascript", "node"},
      {"rust", "rustc (no cargo)"},
      {"latex", "pdflatex"},
      {"dot", "Graphviz dot"}};
  for (Syntax& x : t) x.toolchain = toolchains.at(x.name);
  return t;
}

}  // namespace

const std::vector<Syntax>& targets() {
  static const std::vector<Syntax> table = make_targets();
  return table;
}

const Syntax& syntax(const std::string& name) {
  std::string known;
  for (const auto& s : targets()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw std::invalid_argument("unknown target '" + name + "' (expected " + known + ")");
}

}  // namespace cgagen::emit
