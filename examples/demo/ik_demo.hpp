// The demo's inverse-kinematics scenes: on the loaded character (BCN_Epileptic by default), TwoBoneIKJob
// makes the right hand (B_UpperArm_Right -> B_ForeArm_Right -> B_Hand_Right) reach a target above the
// shoulder, and ChainIKJob bends the spine and the right arm until the hand reaches low in front of the right
// knee; the results are checked and drawn (ik_demo.cpp).
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

// The same for ChainIKJob on the chain B_Spine1 ... B_Hand_Right (8 free joints), the target a third of the
// chain's length in front of the right knee (B_Knee_Right): one line starting "IK chain:" (the hand's
// distance relative to the chain's length, the iterations), out_dir/ik-chain-reach.png. Throws when the hand misses by more than 1e-4 of the
// chain's length; a character without that chain prints why and returns "".
std::string ik_chain_reach(const cga::Character& ch, const std::string& out_dir);

}  // namespace demo
