// Emitters: Program -> source text in one of several languages, through the text templates in templates/
// (files a user can edit; placeholders are {{name}}). See docs/generator.md for the generated interfaces.
//
// A target is data: one `Syntax` record (gen/emit/targets.cpp, the table `targets()`) says how the language
// spells literals, math calls, parameters, outputs, temporaries, blade lists and comments, and
// templates/<name>/ holds its file and function templates. Adding a language is a record, its templates and
// its tests (tests/targets); the CLI (`--target list`), cgagen_generate() (`--target-extension NAME`) and
// the docs all read the same table. emit/statements.hpp prints a Program as statements for a C-family
// function body instead of a file (cgagen --gpc); emit/printer.hpp prints one expression for both.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "opt/program.hpp"

namespace cgagen::emit {

// One precision a target emits a function for.
struct Precision {
  std::string type;       // "float", "double", "f32"; "" where the language has one number type
  bool single = false;    // literals take the target's single-precision suffix
  std::string fn_suffix;  // appended to the function name ("_f32" in Rust, "" where overloading exists)
  std::string before;     // text around the function (e.g. an #ifdef for OpenCL's double)
  std::string after;
};

// How a language spells a straight-line kernel. Patterns use ${key} placeholders (listed per field).
struct Syntax {
  enum class Kind { Code, Dataflow };  // Dataflow: the program's dependency graph (dot), no expressions
  std::string name;                    // --target NAME, the folder under templates/
  std::string extension;               // ".hpp"; the file template is templates/NAME/file<ext>.in
  std::string summary;                 // one line for `--target list -v` and the docs
  std::string toolchain;               // what tests/targets compiles or runs it with (`--target list -v`)
  Kind kind = Kind::Code;
  std::vector<Precision> precisions;   // one function per entry, in this order, joined by a blank line
  std::string single_suffix;           // literal suffix in single precision ("f")
  std::string double_suffix;           // literal suffix in double precision
  std::string math_prefix;             // before a math function's name ("std::", "np.", "${T}::")
  std::map<std::string, std::string> math_names;  // renamed functions; a value containing "${" is a
                                                   // whole pattern with ${args}
  std::string call = "${fn}(${args})";  // a call: ${fn} (prefix + name), ${args}
  // if/else as a select (docs/language.md): ${x} when "${a} ${op} ${b}" holds, else ${y}; ${op} is <, <= or
  // == as spelled in compare_names.
  std::string select = "(${a} ${op} ${b} ? ${x} : ${y})";
  // The same where the select is a whole expression (a right-hand side, an argument, a branch), for targets
  // whose compiler warns about parentheses there (Rust's unused_parens); empty: select.
  std::string select_bare;
  std::map<std::string, std::string> compare_names;  // "<=" -> "\\le" (LaTeX); others as written
  std::string mul = " * ", div = " / ";
  std::string negate = "-${x}";        // a negated operand ${x} (printed as an operand of *)
  std::string constant;                // a literal ${value} where it is not a number of the language
                                       // (a SIMD lane vector: hn::Set(d, ${value})); empty: the literal itself
  std::string comment = "//";          // line comment
  std::string qualifiers;              // {{qualifiers}} of the function template ("inline", CUDA's)
  std::string indent = "  ";           // body indentation
  std::string scalar_param;            // ${T} ${name}
  std::string mv_param;                // ${T} ${name} ${n}
  std::string out_param;               // ${T} ${name} ${n}; empty: outputs are returned (see below)
  std::string element = "${name}[${k}]";        // blade k of a multivector parameter or output
  std::string out_element;             // blade k of an output where it differs (WGSL's pointers); empty: element
  std::string temp;                    // ${T} ${name} ${value}
  std::string assign;                  // ${elem} ${value} ${blade} ${c} (the comment token)
  // Returned outputs (out_param empty): each declared with out_decl, then return_stmt.
  std::string out_decl;                // ${T} ${name} ${n}
  std::string return_item = "${name}";  // ${name}
  std::string return_stmt;             // ${items}, joined by ", "
  std::string unused;                  // a statement for an input no value reads (${name}); empty: none
  // A multivector input's blade copied into a local before the body's first statement: ${T} ${name} (the
  // local) ${elem} (the parameter's element). Empty: the body reads the parameter in place. With pointer
  // parameters (C++) the copies let the compiler keep inputs in registers across the output stores, which
  // it must otherwise assume may change them; they also make a call whose output aliases an input correct.
  std::string load;
  std::string prologue;                // first body line(s); ${splat}: inputs joined by ", " with
  std::string splat_scalar = "${name}", splat_mv = "${name}";  // these forms
  std::string blade_list;              // one line per output: ${fn} ${out} ${n} ${list}
  std::string blade_quote = "\"";      // around each blade name in ${list}
  bool glsl_pack = false;              // --pack / --return apply
  // A lane-wise target (simd): besides the kernel, a batch entry runs it over many elements. Each input is
  // a stream parameter (batch_in), loaded into lanes before the call (batch_load_scalar / _mv: ${name}
  // the stream, ${lanes} the lanes, ${n} the blades), passed as ${lanes}; each output is declared as lanes
  // (batch_out_decl), stored after the call (batch_store). The lanes of NAME are spelt lanes_NAME (a
  // reserved prefix of the target). The function template gets {{batch_params}}, {{batch_loads}},
  // {{batch_args}}, {{batch_stores}} and {{batch_names}} (the stream parameters' names, for a forwarding
  // call); templates/NAME/dispatch.in, where it exists, is filled per program into the file's
  // {{dispatch}}. Empty batch_in: no batch entry, and those placeholders are empty.
  std::string batch_in, batch_out, batch_load_scalar, batch_load_mv, batch_out_decl, batch_store;
  // A staged kernel's NAME_prepare printed by another target's record and templates (simd: cpp's scalar
  // functions, once per batch) into the file's {{scalar_functions}}; empty: by this target, into {{functions}}.
  std::string scalar_twin;
  // Identifiers (emit/names.hpp): words a name must not be, prefixes it must not start with, and whether
  // "__" is reserved anywhere in a name (then a run of underscores is spelt as one).
  std::set<std::string> reserved;
  std::vector<std::string> reserved_prefixes;
  bool single_underscores = false;
  std::string (*ident)(const std::string&) = nullptr;  // identifier spelling (LaTeX), null: names.hpp's
  std::string (*text)(const std::string&) = nullptr;   // escaping of blade names in text, null: as is
};

// The table of targets, in `--target list` order.
const std::vector<Syntax>& targets();
// The record of NAME; throws std::invalid_argument naming the known targets.
const Syntax& syntax(const std::string& name);

// A target by name (a handle into the table). Target::Cpp etc. remain for the built-in C-family targets.
struct Target {
  const char* name = "cpp";
  const Syntax& syntax() const { return emit::syntax(name); }
  friend bool operator==(const Target& a, const Target& b) { return std::string(a.name) == b.name; }
  static const Target Cpp, Glsl, Cuda;
};
Target parse_target(const std::string& text);  // a name from targets(); throws std::invalid_argument
std::string file_extension(Target t);          // ".hpp" | ".glsl" | ".cuh" | ...

// How a GLSL parameter is passed: as a float array (default) or packed in a vector/matrix type. A staged
// kernel's prepared values (the body's input `prepared`) can also come from a uniform block (Block: no
// parameter; `layout(std140) uniform NAME_prepared_block { vec4 NAME_prepared[(K+3)/4]; };` declared before
// the body) or a storage buffer of many prepared sets (Buffer: an `int prepared_index` parameter selects
// set i of `layout(std430) readonly buffer NAME_prepared_buffer { float NAME_prepared[]; };`, values
// i*K ... i*K+K-1; GLSL 4.30). The prepare function still writes a float[K] the host uploads.
enum class Pack { Array, Mat3x4, Vec4, Vec3, Float, Block, Buffer };
Pack parse_pack(const std::string& text);  // "mat3x4" | "vec4" | "vec3" | "float" | "block" | "buffer"

// What a packing is, as data: one row per Pack in one table (emit.cpp); the emitter reads the row's fields
// and never asks which packing it has. Patterns (fill_pattern) take ${name} (the parameter), ${k} (the
// blade), ${row} = k / 4, ${col} = k % 4, ${store} (the block or buffer of the prepared values), ${K} (their
// count), ${rows} = (K+3)/4 and ${last} = K - 1.
struct Packing {
  Pack kind;
  const char* name;   // the --pack spelling, and the GLSL type of a Typed parameter
  size_t capacity;    // the blades it holds (SIZE_MAX: any number)
  enum class Param {
    Array,  // the target's own multivector parameter (a float array)
    Typed,  // `in TYPE NAME` / `out TYPE NAME`
    None,   // no parameter: the values come from a uniform block
    Index,  // `int prepared_index`: the values come from a set of a storage buffer
  } param;
  const char* element;      // blade k; "" for the target's own element pattern
  bool pads;                // an output fills the type's unused elements with 0
  bool prepared_only;       // only for a staged kernel's prepared values
  const char* declaration;  // what the body's file declares before it ("" for nothing)
};
const Packing& packing(Pack p);

struct EmitOptions {
  Target target = Target::Cpp;
  std::string template_dir;      // empty: the built-in CGAGEN_TEMPLATE_DIR
  std::string script_name;       // for the header comment (a file name, not a path, to stay reproducible)
  std::map<std::string, Pack> pack;  // GLSL only: input or output name -> packing
  std::string return_output;     // GLSL only: this output is the return value
};

// The whole file text. Throws std::runtime_error on a missing template or a bad pack/return option.
std::string emit(const opt::Program& program, const EmitOptions& options);
// Several programs as functions of one file, in order (a staged kernel: {prepare, body}, opt/stage.hpp).
// Each is printed exactly as emit() prints a single program; the file lists all their blade lists and inputs.
std::string emit(const std::vector<const opt::Program*>& programs, const EmitOptions& options);

// The functions of independent programs (a generated library's kernels), each printed as emit() prints a
// program, their names spelt together; no file template, no blade lists.
std::string emit_functions(const std::vector<const opt::Program*>& programs, const EmitOptions& options);

// Replaces each {{key}} with values[key]; throws std::runtime_error (naming the template) for a
// placeholder without a value or an unterminated one.
std::string fill_template(const std::string& text, const std::map<std::string, std::string>& values,
                          const std::string& template_name);

// Replaces each ${key} with values[key] (the records' patterns); an unknown key is a logic error.
std::string fill_pattern(const std::string& pattern, const std::map<std::string, std::string>& values);

// Numeric literal of an exact rational in the target's syntax ("0.5", "0.5f", "(1.0 / 3.0)").
std::string literal(const GiNaC::numeric& value, Target target, bool single_precision);

// BINDIR/../share/cgagen/templates next to the running executable (an installed cgagen, prefix relocatable),
// else the source tree's templates/ (CGAGEN_TEMPLATE_DIR, a cgagen run from its build tree).
std::string default_template_dir();

}  // namespace cgagen::emit
