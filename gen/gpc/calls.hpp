// The GPC functions in the C text of a source (cgagen --gpc): mv_from_array statements, which declare a
// block's inputs, and to_array / mv_to_array / mv_get_bladecoeff, which read a block's outputs and become
// C expressions and statements over the locals the block declares (docs/gpc.md has the contract).
#pragma once

#include <string>
#include <vector>

#include "algebra/blade.hpp"
#include "front/ast.hpp"
#include "gpc/scan.hpp"

namespace cgagen::gpc {

// A replacement of text[begin, end) (same number of lines: the text ends in as many '\n' as it replaces).
struct Edit {
  size_t begin = 0, end = 0;
  std::string text;
};

// `NAME = mv_from_array(ARRAY, BLADE, ...);`: blade k of input NAME is sign[k] * ARRAY[k].
struct InputDecl {
  std::string name;
  front::SourceLoc name_loc, fn_loc;
  std::string array;  // as written
  std::vector<algebra::BladeIndex> blades;
  std::vector<int> signs;
  std::vector<front::SourceLoc> blade_locs;
};

// One output of a compiled block: its local's name and blades (emit/statements.hpp declares it).
struct OutputShape {
  std::string name;
  std::vector<algebra::BladeIndex> blades;
};

// A compiled block as the C text after it sees it.
struct BlockOutputs {
  int index = 0;         // 1-based
  size_t visible_from;   // offset where the C text after its script section starts
  std::vector<OutputShape> outputs;
};

// Reads the GPC calls of text[begin, end) and appends the edits that replace them. `blocks`: the blocks
// compiled so far, in order (an output name refers to the last block before the call that has it). When
// `inputs` is given (the text between `#pragma gpc begin` and `#pragma clucalc begin`), mv_from_array
// statements are read into it and removed; elsewhere mv_from_array is an error. `type`: the number type of
// the outputs (to_array's std::array<type, n>, the literal 0 of a blade an output lacks).
void rewrite_calls(const Text& text, size_t begin, size_t end, const std::vector<BlockOutputs>& blocks,
                   const std::string& type, std::vector<InputDecl>* inputs, std::vector<Edit>& edits);

}  // namespace cgagen::gpc
