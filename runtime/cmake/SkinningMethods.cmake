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
# as NAME:BLADES (the blade count), in declaration order: a skinning script declares them in the order of its
# #pragma in2out line (the generated function's parameter order).
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

# The multivectors a script declares with `//#pragma KIND NAME BLADE...` (KIND a regex: input, output or
# (input|output)), each as NAME:BLADES (the blade count), in declaration order.
function(_cga_skinning_script_declared script kind out)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${script})
  file(STRINGS ${script} _decls REGEX "^//#pragma ${kind} ")
  set(_list)
  foreach(_d ${_decls})
    string(REGEX REPLACE "^//#pragma ${kind} +" "" _d "${_d}")
    string(REGEX REPLACE " +" ";" _words "${_d}")
    list(POP_FRONT _words _name)
    list(LENGTH _words _count)
    list(APPEND _list ${_name}:${_count})
  endforeach()
  set(${out} ${_list} PARENT_SCOPE)
endfunction()

function(cga_skinning_script_inputs script out)
  _cga_skinning_script_declared(${script} input _inputs)
  # The glue passes the inputs in this order: it must be the generated function's (#pragma in2out).
  file(STRINGS ${script} _in2out REGEX "^#pragma in2out ")
  if(_in2out)
    string(REGEX REPLACE "^#pragma in2out +| *->.*$" "" _params "${_in2out}")
    string(REGEX REPLACE " *, *" ";" _params "${_params}")
    set(_i 0)
    foreach(_in ${_inputs})
      string(REGEX REPLACE ":[0-9]+$" "" _name "${_in}")
      list(GET _params ${_i} _param)
      if(NOT _param STREQUAL _name)
        message(FATAL_ERROR "${script}: the #pragma input declarations must follow the #pragma in2out order (parameter ${_i} is ${_param}, declaration ${_i} is ${_name})")
      endif()
      math(EXPR _i "${_i} + 1")
    endforeach()
  endif()
  set(${out} ${_inputs} PARENT_SCOPE)
endfunction()

# The --pack arguments of a skinning script for the GLSL targets: every multivector input and output of 3 or
# 4 blades as vec3 / vec4 (an entry is a run of vec4s; the positions and normals are vec3).
function(cga_skinning_script_pack script out)
  _cga_skinning_script_declared(${script} "(input|output)" _decls)
  set(_pack)
  foreach(_d ${_decls})
    string(REGEX MATCH "[0-9]+$" _count "${_d}")
    string(REGEX REPLACE ":[0-9]+$" "" _name "${_d}")
    if(_count EQUAL 4)
      list(APPEND _pack ${_name}=vec4)
    elseif(_count EQUAL 3)
      list(APPEND _pack ${_name}=vec3)
    endif()
  endforeach()
  set(${out} ${_pack} PARENT_SCOPE)
endfunction()

# The desktop GL programs' skin() of method <id>: its skin_<id>() (cga_skinning_glsl_method_skin, below) on
# the instance's palette, PALETTE_STRIDE vec4s per entry read through palette_at(vec4 index); the normal
# renormalized.
#   skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on)
# Data movement only: the blend itself is the generated function.
function(cga_skinning_glsl_skin id out)
  cga_skinning_glsl_method_skin(${id} _method)
  set(${out} "${_method}
const int PALETTE_STRIDE = ${CGA_SKIN_${id}_VEC4S};

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  vec3 tn;
  skin_${id}(PALETTE_STRIDE * base, j, w, p, n, op, tn);
  on = normals ? normalize(tn) : vec3(0.0);
}
" PARENT_SCOPE)
endfunction()

# ---- One shader for every method (the web page's WebGL 2 and WebGPU shaders): a skin_<id>() per method
# that reads its entries from anywhere in one palette, and a skin() that picks one by the method's code. The
# palette holds every method's prepared palette of `entries` entries one after the other, in table order, so
# method m's entry 0 is vec4 entries x (the VEC4S of the rows before m). Data movement only: the blends are
# the generated functions (GLSL ES .essl, WGSL .wgsl), which the includer puts in front.
#
# cga_skinning_glsl_method_skin(<id> <out>)  GLSL (ES 3.00 and desktop alike), palette_at(int) supplied:
#   void skin_<id>(int first, ivec4 j, vec4 w, vec3 p, vec3 n, out vec3 op, out vec3 on)
# cga_skinning_wgsl_method_skin(<id> <out>)  WGSL, fn palette_at(i: i32) -> vec4<f32> supplied:
#   fn skin_<id>(first: i32, j: vec4<i32>, w: vec4<f32>, p: vec3<f32>, n: vec3<f32>,
#                op: ptr<function, vec3<f32>>, on: ptr<function, vec3<f32>>)
# first: the vec4 where the method's entry 0 starts; on: unnormalized (the caller normalizes, once).
# cga_skinning_glsl_dispatch(<out>), cga_skinning_wgsl_dispatch(<out>): every method's skin_<id>() (as above)
# and then skin(method, entries, j, w, p, n, op, on) (WGSL: pointers op, on) over the table's codes; an
# unknown code gives the rest pose. Call cga_read_skinning_methods() first.

# The entry inputs of method <id>'s blend as "ENTRY:SLOT:BLADES", checked against its VEC4S and its outputs
# (p and n, 3 blades each: what the glue hands back).
function(_cga_skinning_entry_inputs id out)
  set(_blend ${CGA_SKIN_${id}_BLEND})
  set(_k ${CGA_SKIN_${id}_VEC4S})
  set(_script ${CGA_SKINNING_SCRIPT_DIR}/${_blend}.clu)
  cga_skinning_script_inputs(${_script} _inputs)
  list(LENGTH _inputs _n)
  math(EXPR _expect "4 * ${_k}")
  if(NOT _n EQUAL _expect)
    message(FATAL_ERROR "${_blend}.clu: method ${id} has ${_k} vec4s per entry, so 4 x ${_k} multivector inputs, not ${_n}")
  endif()
  file(STRINGS ${_script} _outs REGEX "^//#pragma output ")
  if(NOT _outs MATCHES "^//#pragma output p e1 e2 e3;//#pragma output n e1 e2 e3$")
    message(FATAL_ERROR "${_blend}.clu: the glue expects the outputs p and n (e1 e2 e3 each), found '${_outs}'")
  endif()
  set(_list)
  set(_i 0)
  foreach(_in ${_inputs})
    string(REGEX REPLACE "^.*:" "" _blades "${_in}")
    if(NOT _blades EQUAL 3 AND NOT _blades EQUAL 4)
      message(FATAL_ERROR "${_blend}.clu: entry input ${_in} has ${_blades} blades (3 or 4 fit a vec4)")
    endif()
    math(EXPR _entry "${_i} / ${_k}")
    math(EXPR _slot "${_i} % ${_k}")
    list(APPEND _list ${_entry}:${_slot}:${_blades})
    math(EXPR _i "${_i} + 1")
  endforeach()
  set(${out} ${_list} PARENT_SCOPE)
endfunction()

function(cga_skinning_glsl_method_skin id out)
  set(_blend ${CGA_SKIN_${id}_BLEND})
  set(_k ${CGA_SKIN_${id}_VEC4S})
  _cga_skinning_entry_inputs(${id} _inputs)
  set(_args)
  foreach(_in ${_inputs})
    string(REPLACE ":" ";" _f "${_in}")
    list(GET _f 0 _entry)
    list(GET _f 1 _slot)
    list(GET _f 2 _blades)
    set(_arg "palette_at(e${_entry} + ${_slot})")
    if(_blades EQUAL 3)
      string(APPEND _arg ".xyz")
    endif()
    list(APPEND _args "${_arg}")
  endforeach()
  list(JOIN _args ",\n      " _args)
  set(${out} "// ${CGA_SKIN_${id}_NAME} (from the method table): the generated ${_blend} on four entries of ${_k} vec4s.
void skin_${id}(int first, ivec4 j, vec4 w, vec3 p, vec3 n, out vec3 op, out vec3 on) {
  int e0 = first + ${_k} * j[0];
  int e1 = first + ${_k} * j[1];
  int e2 = first + ${_k} * j[2];
  int e3 = first + ${_k} * j[3];
  ${_blend}(${_args},
      w[0], w[1], w[2], w[3], p.x, p.y, p.z, n.x, n.y, n.z, op, on);
}
" PARENT_SCOPE)
endfunction()

function(cga_skinning_wgsl_method_skin id out)
  set(_blend ${CGA_SKIN_${id}_BLEND})
  set(_k ${CGA_SKIN_${id}_VEC4S})
  _cga_skinning_entry_inputs(${id} _inputs)
  # The generated WGSL takes array<f32, N> values: each vec4 is read once and spelled out.
  set(_reads)
  set(_args)
  set(_i 0)
  foreach(_in ${_inputs})
    string(REPLACE ":" ";" _f "${_in}")
    list(GET _f 0 _entry)
    list(GET _f 1 _slot)
    list(GET _f 2 _blades)
    string(APPEND _reads "  let v${_i} = palette_at(e${_entry} + ${_slot});\n")
    if(_blades EQUAL 3)
      list(APPEND _args "array<f32, 3>(v${_i}.x, v${_i}.y, v${_i}.z)")
    else()
      list(APPEND _args "array<f32, 4>(v${_i}.x, v${_i}.y, v${_i}.z, v${_i}.w)")
    endif()
    math(EXPR _i "${_i} + 1")
  endforeach()
  list(JOIN _args ",\n      " _args)
  set(${out} "// ${CGA_SKIN_${id}_NAME} (from the method table): the generated ${_blend} on four entries of ${_k} vec4s.
fn skin_${id}(first: i32, j: vec4<i32>, w: vec4<f32>, p: vec3<f32>, n: vec3<f32>,
              op: ptr<function, vec3<f32>>, on: ptr<function, vec3<f32>>) {
  let e0 = first + ${_k} * j[0];
  let e1 = first + ${_k} * j[1];
  let e2 = first + ${_k} * j[2];
  let e3 = first + ${_k} * j[3];
${_reads}  var tp: array<f32, 3>;
  var tn: array<f32, 3>;
  ${_blend}(${_args},
      w[0], w[1], w[2], w[3], p.x, p.y, p.z, n.x, n.y, n.z, &tp, &tn);
  *op = vec3<f32>(tp[0], tp[1], tp[2]);
  *on = vec3<f32>(tn[0], tn[1], tn[2]);
}
" PARENT_SCOPE)
endfunction()

# The dispatch of either language (lang glsl or wgsl).
function(_cga_skinning_dispatch lang out)
  set(_text "// Every method of runtime/include/cga/runtime/skinning_methods.hpp, its code its row; generated by\n")
  string(APPEND _text "// runtime/cmake/SkinningMethods.cmake.\n")
  set(_cases "")
  set(_code 0)
  set(_vec4s_before 0)
  foreach(_id ${CGA_SKINNING_METHOD_IDS})
    if(lang STREQUAL "glsl")
      cga_skinning_glsl_method_skin(${_id} _skin)
    else()
      cga_skinning_wgsl_method_skin(${_id} _skin)
    endif()
    # (string(APPEND), not a list: the text holds semicolons)
    string(APPEND _cases "  if (method == ${_code}) {\n"
                         "    skin_${_id}(${_vec4s_before} * entries, j, w, p, n, op, on);\n    return;\n  }\n")
    string(APPEND _text "\n${_skin}")
    math(EXPR _code "${_code} + 1")
    math(EXPR _vec4s_before "${_vec4s_before} + ${CGA_SKIN_${_id}_VEC4S}")
  endforeach()
  if(lang STREQUAL "glsl")
    string(APPEND _text "
// Method `method` (its row in the table) on a palette of every method's `entries` entries in table order
// (${_vec4s_before} vec4s per entry in all).
const int SKINNING_METHOD_COUNT = ${_code};

void skin(int method, int entries, ivec4 j, vec4 w, vec3 p, vec3 n, out vec3 op, out vec3 on) {
${_cases}  op = p;
  on = n;
}
")
  else()
    string(APPEND _text "
// Method `method` (its row in the table) on a palette of every method's `entries` entries in table order
// (${_vec4s_before} vec4s per entry in all).
const SKINNING_METHOD_COUNT: i32 = ${_code};

fn skin(method: i32, entries: i32, j: vec4<i32>, w: vec4<f32>, p: vec3<f32>, n: vec3<f32>,
        op: ptr<function, vec3<f32>>, on: ptr<function, vec3<f32>>) {
${_cases}  *op = p;
  *on = n;
}
")
  endif()
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()

function(cga_skinning_glsl_dispatch out)
  _cga_skinning_dispatch(glsl _text)
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()

function(cga_skinning_wgsl_dispatch out)
  _cga_skinning_dispatch(wgsl _text)
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()
