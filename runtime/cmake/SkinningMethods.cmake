# The skinning method table (runtime/include/cga/runtime/skinning_methods.hpp) for CMake, and the packing of
# the skinning scripts' inputs for the shading languages. Included by generated/, runtime/gpu/, runtime/cuda/
# and web/: they iterate the table; none of them names a method.
#
# cga_read_skinning_methods() sets in the caller's scope:
#   CGA_SKINNING_METHOD_IDS    the ids in table order (a method's GPU code is its index)
#   CGA_SKIN_<id>_NAME         the CLI name (cga-motors)
#   CGA_SKIN_<id>_PALETTE      matrices, dual_quats or motors
#   CGA_SKIN_<id>_BONE         the per-bone script's stem, or none
#   CGA_SKIN_<id>_BLEND        the per-vertex blend script's stem
#   CGA_SKIN_<id>_VEC4S        vec4s per prepared entry
#   CGA_SKIN_<id>_COLOUR       r;g;b
# cga_skinning_script_inputs(<script> <out>) sets <out> to the script's multivector inputs (#pragma input), each
# as NAME:BLADES (the blade count), in the order of its #pragma in2out line when it has one.
get_filename_component(CGA_SKINNING_METHODS_HPP ${CMAKE_CURRENT_LIST_DIR}/../include/cga/runtime/skinning_methods.hpp ABSOLUTE)
get_filename_component(CGA_SKINNING_SCRIPT_DIR ${CMAKE_CURRENT_LIST_DIR}/../scripts/skin ABSOLUTE)

function(cga_read_skinning_methods)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CGA_SKINNING_METHODS_HPP})
  # The rows end in the macro's line continuation: drop it before splitting (a trailing \ escapes CMake's ;).
  file(READ ${CGA_SKINNING_METHODS_HPP} _text)
  string(REPLACE "\\\n" "\n" _text "${_text}")
  string(REGEX MATCHALL "\n  X\\([^\n]*" _rows "${_text}")
  set(_ids)
  foreach(_row ${_rows})
    if(NOT _row MATCHES "^\n  X\\(([a-z0-9_]+), \"([a-z0-9-]+)\", (matrices|dual_quats|motors), ([a-z0-9_]+), ([a-z0-9_]+), ([1-4]), ([0-9.]+)f, ([0-9.]+)f, ([0-9.]+)f\\)")
      message(FATAL_ERROR "${CGA_SKINNING_METHODS_HPP}: cannot read the row '${_row}' (ID, \"NAME\", PALETTE, BONE, BLEND, VEC4S, Rf, Gf, Bf)")
    endif()
    set(_id ${CMAKE_MATCH_1})
    list(APPEND _ids ${_id})
    set(CGA_SKIN_${_id}_NAME ${CMAKE_MATCH_2} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_PALETTE ${CMAKE_MATCH_3} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_BONE ${CMAKE_MATCH_4} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_BLEND ${CMAKE_MATCH_5} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_VEC4S ${CMAKE_MATCH_6} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_COLOUR "${CMAKE_MATCH_7};${CMAKE_MATCH_8};${CMAKE_MATCH_9}" PARENT_SCOPE)
    foreach(_script ${CMAKE_MATCH_4} ${CMAKE_MATCH_5})
      if(NOT _script STREQUAL "none" AND NOT EXISTS ${CGA_SKINNING_SCRIPT_DIR}/${_script}.clu)
        message(FATAL_ERROR "${CGA_SKINNING_METHODS_HPP}: method ${_id} names ${_script}, which is not a script in ${CGA_SKINNING_SCRIPT_DIR}")
      endif()
    endforeach()
  endforeach()
  if(NOT _ids)
    message(FATAL_ERROR "${CGA_SKINNING_METHODS_HPP}: no method rows")
  endif()
  set(CGA_SKINNING_METHOD_IDS ${_ids} PARENT_SCOPE)
endfunction()

function(cga_skinning_script_inputs script out)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${script})
  file(STRINGS ${script} _decls REGEX "^//#pragma input ")
  set(_inputs)
  foreach(_d ${_decls})
    string(REGEX REPLACE "^//#pragma input +" "" _d "${_d}")
    string(REGEX REPLACE " +" ";" _words "${_d}")
    list(POP_FRONT _words _name)
    list(LENGTH _words _count)
    list(APPEND _inputs ${_name}:${_count})
  endforeach()
  set(${out} ${_inputs} PARENT_SCOPE)
endfunction()

# The --pack arguments of a skinning script for the GLSL targets: every multivector input and output of 3 or
# 4 blades as vec3 / vec4 (an entry is a run of vec4s; the positions and normals are vec3).
function(cga_skinning_script_pack script out)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${script})
  file(STRINGS ${script} _decls REGEX "^//#pragma (input|output) ")
  set(_pack)
  foreach(_d ${_decls})
    string(REGEX REPLACE "^//#pragma (input|output) +" "" _d "${_d}")
    string(REGEX REPLACE " +" ";" _words "${_d}")
    list(POP_FRONT _words _name)
    list(LENGTH _words _count)
    if(_count EQUAL 4)
      list(APPEND _pack ${_name}=vec4)
    elseif(_count EQUAL 3)
      list(APPEND _pack ${_name}=vec3)
    endif()
  endforeach()
  set(${out} ${_pack} PARENT_SCOPE)
endfunction()

# The GLSL skin() of method <id> (desktop GLSL and GLSL ES alike): its generated blend on four prepared
# entries read through palette_at(vec4 index), PALETTE_STRIDE vec4s per entry; the normal renormalized.
#   skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on)
# Data movement only: the blend itself is the generated function.
function(cga_skinning_glsl_skin id out)
  set(_blend ${CGA_SKIN_${id}_BLEND})
  set(_k ${CGA_SKIN_${id}_VEC4S})
  cga_skinning_script_inputs(${CGA_SKINNING_SCRIPT_DIR}/${_blend}.clu _inputs)
  list(LENGTH _inputs _n)
  math(EXPR _expect "4 * ${_k}")
  if(NOT _n EQUAL _expect)
    message(FATAL_ERROR "${_blend}.clu: method ${id} has ${_k} vec4s per entry, so 4 x ${_k} multivector inputs, not ${_n}")
  endif()
  set(_args)
  set(_i 0)
  foreach(_in ${_inputs})
    string(REGEX REPLACE "^.*:" "" _blades "${_in}")
    math(EXPR _entry "${_i} / ${_k}")
    math(EXPR _slot "${_i} % ${_k}")
    set(_arg "palette_at(e${_entry} + ${_slot})")
    if(_blades EQUAL 3)
      string(APPEND _arg ".xyz")
    elseif(NOT _blades EQUAL 4)
      message(FATAL_ERROR "${_blend}.clu: entry input ${_in} has ${_blades} blades (3 or 4 fit a vec4)")
    endif()
    list(APPEND _args "${_arg}")
    math(EXPR _i "${_i} + 1")
  endforeach()
  list(JOIN _args ",\n        " _args)
  set(${out} "// skin() of ${id} (from the method table): the generated ${_blend} on four prepared entries.
const int PALETTE_STRIDE = ${_k};

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  int e0 = PALETTE_STRIDE * (base + j[0]);
  int e1 = PALETTE_STRIDE * (base + j[1]);
  int e2 = PALETTE_STRIDE * (base + j[2]);
  int e3 = PALETTE_STRIDE * (base + j[3]);
  vec3 tn;
  ${_blend}(${_args},
        w[0], w[1], w[2], w[3], p.x, p.y, p.z, n.x, n.y, n.z, op, tn);
  on = normals ? normalize(tn) : vec3(0.0);
}
" PARENT_SCOPE)
endfunction()
