// Automatic staging: an optimized Program split into a per-batch stage and a per-element stage.
//
// Inputs marked uniform (`#pragma uniform NAME...`, `--uniform A,B`, cgagen_generate(UNIFORM ...)) are fixed
// across a batch (a motor, key poses, a blend weight); every other input varies per element (a point's x, y,
// z). The staged form is two ordinary Programs, so every emitter prints both with no per-target code:
//   NAME_prepare(uniforms) -> prepared[K]        everything that depends on uniform inputs only
//   NAME(prepared[K], per-element inputs) -> the kernel's outputs
// See stage.cpp for how the split is found and docs/generator.md for the measured results.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "opt/program.hpp"
#include "opt/report.hpp"

namespace cgagen::opt {

struct StagedProgram {
  Program prepare;  // inputs: the uniform inputs; one output "prepared" of K values (labelled, see labels)
  Program body;     // inputs: "prepared" (K values) then the per-element inputs; the kernel's outputs
  std::vector<std::string> uniforms;  // the uniform inputs' names, in input order
  std::vector<std::string> at;        // stage_at: the named values of the cut (empty: staged by rate)
};

// The uniform inputs of the kernel: those of its `#pragma uniform` lines and those named on the command line
// (cli), in input order, without repeats. A pragma naming something that is not an input is a CompileError
// at the name; a command-line name that is not an input throws std::invalid_argument.
std::vector<std::string> uniform_inputs(const Kernel& kernel, const std::vector<std::string>& cli);

// The staged form of an optimized program (any level; at -O2 the pass pipeline runs on each stage).
// Deterministic. Minimizes the per-element cost first, then K, then the prepare cost.
StagedProgram stage(const Program& program, const std::vector<std::string>& uniforms);

// The kernel split at the named values (--stage-at A,B; stage_at.cpp): NAME_prepare computes their
// coefficients (one prepared value each, in the order of the names) from every input the rest does not read,
// NAME the outputs from them and the inputs the rest reads. `uniforms` are then the prepare's inputs. A name the script does not
// assign, an output, or an input read on both sides of the cut throws std::invalid_argument.
StagedProgram stage_at(const Kernel& kernel, const std::vector<std::string>& names, Level level);

// "kernel NAME at -O2, staged (uniform: M)\nprepare: ...\nper element: ...\nprepared values: K\n..."
std::string format_staged_stats(const StagedProgram& staged);

// prepare then body on the given inputs (all of the unstaged kernel's inputs), as the emitted code computes.
std::vector<EvalLine> evaluate_staged(const StagedProgram& staged, const InputValues& inputs);

// The largest difference between the staged and unstaged values relative to max(1, |unstaged|), and
// whether it is within tolerance (1e-9): --eval's check that prepare o body equals the unstaged kernel.
struct StagedCheck {
  double max_rel_error = 0;
  bool ok = true;
};
StagedCheck compare_staged(const std::vector<EvalLine>& staged, const std::vector<EvalLine>& unstaged);

}  // namespace cgagen::opt
