// cgagen --help: the synopsis and every option (docs/generator.md's "## CLI" and docs/cgagen.1 are checked
// against it both ways by the tests docs/cgagen_options and install/man_page_covers_help).
#pragma once

namespace cgagen {

inline constexpr const char* kUsage = R"(usage: cgagen [options] SCRIPT
       cgagen --gpc [options] SOURCE
       cgagen --library [options] SPEC

Compiles a CluScript (Gaalop/CLUCalc) file into straight-line code. SCRIPT - reads the script from
standard input (diagnostics then name <stdin>, the function is named kernel unless --name is given).

With --gpc, SOURCE is a C, C++ or CUDA file whose `#pragma gpc begin` ... `#pragma gpc end` blocks are
compiled in place (mv_from_array inputs, a `#pragma clucalc` script, to_array / mv_to_array /
mv_get_bladecoeff of its outputs after it; see docs/gpc.md); the rest of the text is copied unchanged.

With --library, SPEC is a library spec (an algebra and named types, see docs/library.md): the output is
a typed library with every operation between the types, each one optimized kernel.

options:
  --algebra NAME|FILE     the geometric algebra (default cga): 2d 3d 2dpga 3dpga cra sta cga gac qga
                          dcga ccga, or a Gaalop definition.csv file
  --target NAME           output language (default cpp); --target list prints the targets,
                          --target list -v one line each with extension, toolchain and summary
  --target-extension NAME print the file extension of target NAME
  -O0 | -O1 | -O2         optimization level (default -O2)
  -o FILE                 write the output to FILE (default: standard output)
  --name NAME             function name: letters, digits and _, not starting with a digit (default:
                          the script's file stem, other bytes as _, a leading digit after a _); a
                          target's reserved word gets a trailing _ in that target
  --templates DIR         emitter templates (default: ../share/cgagen/templates next to the cgagen
                          executable when installed, else the source tree's templates/)
  --pack NAME=KIND        glsl: pass input/output NAME as mat3x4, vec4, vec3 or float; a staged
                          kernel's prepared values also as block (a uniform block) or buffer (a
                          storage buffer of many sets, selected by an int prepared_index)
  --return OUT            glsl: return output OUT instead of an out parameter
  --outputs A,B,...       keep only these outputs of the script (in the script's order); the work
                          only the others need is not emitted
  --jacobian A,B,...      also emit every output's partial derivatives with respect to inputs A, B, ...
                          (a multivector input: each coefficient), as outputs OUT_d_A (also
                          `#pragma jacobian [OUT...] wrt A B`)
  --uniform A,B,...       stage the kernel: inputs A, B, ... are fixed across a batch (also
                          `#pragma uniform A B`); emits NAME_prepare(uniforms) -> prepared values
                          and NAME(prepared, per-element inputs); --stats, --diff, --eval show it
  --stage-at A,B,...      stage the kernel at the named values of the script: NAME_prepare computes
                          them from the inputs they read, NAME the outputs from them and the other
                          inputs (a two-pass batch loop: the prepare once per element)
  --gpc                   SOURCE is a C/C++/CUDA source with GPC blocks: write it with each block compiled
                          (with --algebra, -O, -o, --Werror, --target cpp|cuda|opencl, --type)
  --library               SCRIPT is a library spec: write the library (with -O, -o, --target, --templates,
                          --also; --stats prints each function's op counts instead)
  --also TARGET=FILE      --library: also write the library in TARGET to FILE, from the same build of its
                          functions (repeatable; one run for many targets)
  --type T                --gpc: the number type of the blocks' outputs and temporaries (default float;
                          double or another C type name: literals then have no f suffix)
  --stats                 print op counts instead of code
  --stats-out FILE        write op counts to FILE besides the code
  --diff A B              diff the code of two levels (e.g. --diff -O1 -O2), with the op-count change;
                          with uniforms: unstaged at A against staged at B
  --dump-ast              print the parsed script
  --Werror                treat warnings (a misspelt name that became an input) as errors
  --eval NAME=VALUE ...   evaluate the optimized kernel (values before or after SCRIPT); a multivector input as NAME=v1,v2,...
                          (one value per declared blade); prints OUTPUT BLADE VALUE lines
  --passes                print the -O2 optimizer's passes in run order (name and description)
  --version               print the version (cgagen X.Y.Z)
  --help                  this text

exit status: 0 success; 1 error in the script (FILE:LINE:COL: error: ...) or other failure
(cgagen: error: ...); 2 bad usage.
)";

}  // namespace cgagen
