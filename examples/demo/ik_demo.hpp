// The demo's inverse-kinematics scene: on the loaded character (BCN_Epileptic by default), TwoBoneIKJob
// makes the right hand (B_UpperArm_Right -> B_ForeArm_Right -> B_Hand_Right) reach a target above the
// shoulder, and the result is checked and drawn (ik_demo.cpp).
#pragma once

#include <string>

#include "cga/runtime/character.hpp"

namespace demo {

// Poses clip 0 at half its duration, solves, applies the corrections, recomputes the model pose and prints
// the hand's distance to the target relative to the arm's length (one line starting "IK:"). With a non-empty
// out_dir it also writes out_dir/ik-hand-reach.png (before in grey, after in colour, the target as a red
// marker) and returns its path. Throws std::runtime_error when a job refuses its input or the hand misses
// the target by more than 1e-4 of the arm's length. A character without that arm: prints why, returns "".
std::string ik_hand_reach(const cga::Character& ch, const std::string& out_dir);

}  // namespace demo
