// A Character as bytes, for the trip from the loader's importer process back to the caller (isolated.hpp).
// Both ends are the same build of the same program, so values go in native layout: no versioning, no byte
// order. Clip::keys and Clip::intervals are left out: the receiver builds them from the tracks
// (build_joint_keys), which is cheaper than sending them (16 MB for a long BVH clip).
#pragma once

#include <string>
#include <string_view>

#include "cga/runtime/character.hpp"

namespace cga::io_detail {

std::string encode_character(const Character& ch);
// Throws std::runtime_error when the bytes end early or run past the end of a field.
Character decode_character(std::string_view bytes);

}  // namespace cga::io_detail
