// The pragmas of a script (docs/language.md, "Pragmas"): `output`, `input`, `range`, `uniform`, `normalized`, `versor`,
// `onlyEvaluate`, `in2out`, `normalize`, Gaalop's drawing hints, and clear errors for those cgagen does not
// support. Each is checked where it stands; what it asks of the kernel is recorded in the Kernel (inputs,
// ranges, uniforms, normalized names) or here, for the expander to apply (outputs' blades, values kept,
// normalized outputs, the in2out order).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "algebra/blade.hpp"
#include "expand/kernel.hpp"
#include "front/ast.hpp"

namespace cgagen::expand_pragmas {

// What a pragma needs to know of, and do to, the expander.
class PragmaHost {
 public:
  virtual ~PragmaHost() = default;
  virtual bool is_basis_name(const std::string& name) const = 0;
  virtual bool is_assigned(const std::string& name) const = 0;  // the script assigns it somewhere
  virtual bool is_defined(const std::string& name) const = 0;   // it already has a value here
  // `#pragma input NAME BLADE...`: a multivector input with one symbol per blade, in the pragma's order.
  virtual void declare_input(const std::string& name, const std::vector<algebra::BladeIndex>& blades) = 0;
};

struct OutputPragma {  // `#pragma output NAME BLADE...`
  front::SourceLoc loc;
  std::vector<algebra::BladeIndex> blades;
};

// `#pragma jacobian [OUT...] wrt IN...`: the partial derivatives of the outputs (all of them when none is
// named) with respect to the inputs (a multivector input: each of its coefficients).
struct JacobianPragma {
  front::SourceLoc loc;
  std::vector<UniformName> outputs, wrt;
};

class Pragmas {
 public:
  // Checks and records one pragma statement; throws front::CompileError at the offending word.
  void apply(const front::Stmt& s, Kernel& kernel, PragmaHost& host);

  // `#pragma normalize` seen: later `?x = e;` output e / abs(e).
  bool normalize_outputs() const { return normalize_outputs_; }
  // `#pragma onlyEvaluate NAME`: NAME's values stay in the kernel.
  bool only_evaluate(const std::string& name) const;
  // `#pragma versor NAME...`: the names whose values the script promises are versors (x ~x a scalar).
  const std::vector<UniformName>& versors() const { return versors_; }
  const std::vector<JacobianPragma>& jacobians() const { return jacobians_; }
  // The `#pragma output` of an output, or null.
  const OutputPragma* output(const std::string& name) const;

  // Once the outputs are known: every `#pragma output` names one of them, and `#pragma in2out` orders the
  // kernel's inputs and outputs (every one listed, and only those).
  void check_outputs(const std::function<bool(const std::string&)>& is_output) const;
  void apply_in2out(Kernel& kernel) const;

 private:
  struct In2Out {
    front::SourceLoc loc;
    std::vector<std::string> inputs, outputs;
  };
  void in2out_pragma(const front::Stmt& s);

  std::map<std::string, OutputPragma> outputs_;
  std::set<std::string> only_evaluate_;
  std::optional<In2Out> in2out_;
  bool normalize_outputs_ = false;
  std::vector<UniformName> versors_;
  std::vector<JacobianPragma> jacobians_;
};

}  // namespace cgagen::expand_pragmas
