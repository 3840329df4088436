// The simd target's driver (targets_check simd / simd-aarch64): one C++ program over every script's
// NAME.simd.hpp that runs NAME_batch on all sample rows of a case at once, in one instruction set, with its
// inputs in varied layouts (structure of arrays, array of structures, gathered through an index stream) and
// its outputs stored contiguously or scattered, or with every input broadcast from the first row.
//   drive list                  the instruction sets it can run: "BITS NAME" per line
//   drive CASE BITS layouts     rows on stdin -> outputs per row on stdout
//   drive CASE BITS broadcast   the first row's inputs broadcast (stride 0) to every row
// Dispatch builds (x86) run each ISA through Highway's run-time dispatch; a static build (a cross compile,
// run under qemu) has the one instruction set it was compiled for.
#pragma once

#include <string>
#include <vector>

namespace targets {

struct SimdCase {
  std::string header;          // the generated header's path
  std::string fn, prepare;     // NAME and NAME_prepare as the simd target spells them
  std::vector<size_t> in_sizes;  // the unstaged kernel's inputs, 0 for a scalar
  std::vector<bool> uniform;     // per input: goes to NAME_prepare (a staged case)
  size_t prepared = 0;           // K, 0 unstaged
  std::vector<size_t> out_sizes;
};

// `not_run`: Highway targets (bits) not compiled into a dispatch build: those the CPU running the test lacks,
// whose code the driver could only compile, never run.
std::string simd_driver_source(const std::vector<SimdCase>& cases, bool dispatch, long long not_run = 0);

}  // namespace targets
