// Anchor translation unit of cga::runtime (the library's types are header-only).
#include "cga/runtime/types.hpp"
