# The skinning method table (runtime/skinning_methods.txt, which documents its columns) for CMake, the C++
# header generated from it, and the packing of the skinning scripts' inputs for the shading languages.
# Included by runtime/, generated/, runtime/gpu/, runtime/cuda/, web/ and examples/demo/: they iterate the
# table; none of them names a method.
#
# cga_read_skinning_methods() sets in the caller's scope:
#   CGA_SKINNING_METHOD_IDS    the ids in table order (a method's GPU code is its index)
#   CGA_SKINNING_METHOD_NAMES  the names in table order
#   CGA_SKIN_<id>_NAME         the CLI name (cga-motors)
#   CGA_SKIN_<id>_PALETTE      matrices, dual_quats or motors
#   CGA_SKIN_<id>_BONE         the per-bone script's stem, or none
#   CGA_SKIN_<id>_BLEND        the per-vertex blend script's stem
#   CGA_SKIN_<id>_VEC4S        vec4s per prepared entry
#   CGA_SKIN_<id>_COLOUR       r;g;b
#   CGA_SKIN_<id>_CAPTION      the short caption (pictures, the page)
#   CGA_SKIN_SPLIT_<blend>     the blend script's batch split: its named values (a list), or empty
# cga_write_skinning_methods_header(<include_dir>) writes <include_dir>/cga/runtime/skinning_methods.hpp.
# The C++ header and the shader glue below (GLSL, GLSL ES, WGSL, the CUDA includes) are the templates of
# runtime/cmake/templates filled from the table (cga_skinning_fill_template): the text lives there, the
# functions here compute only what varies per method (argument lists, offsets, the dispatch's cases).
# cga_skinning_script_inputs(<script> <out>) sets <out> to the script's multivector inputs (#pragma input), each
# as NAME:BLADES (the blade count), in declaration order: a skinning script declares them in the order of its
# #pragma in2out line (the generated function's parameter order).
get_filename_component(CGA_SKINNING_METHODS_TABLE ${CMAKE_CURRENT_LIST_DIR}/../skinning_methods.txt ABSOLUTE)
get_filename_component(CGA_SKINNING_SCRIPT_DIR ${CMAKE_CURRENT_LIST_DIR}/../scripts/skin ABSOLUTE)
get_filename_component(CGA_SKINNING_TEMPLATE_DIR ${CMAKE_CURRENT_LIST_DIR}/templates ABSOLUTE)

function(cga_read_skinning_methods)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CGA_SKINNING_METHODS_TABLE})
  file(STRINGS ${CGA_SKINNING_METHODS_TABLE} _lines ENCODING UTF-8)
  set(_ids)
  set(_names)
  set(_number 0)
  set(_b "[ \t]+")  # the column separator
  set(_f "[0-9]*\\.?[0-9]+")  # a colour component (CMake's regexes take 9 groups: R G B are one)
  foreach(_line IN LISTS _lines)
    math(EXPR _number "${_number} + 1")
    if(_line MATCHES "^[ \t]*(#|$)")
      continue()
    endif()
    if(NOT _line MATCHES "^([a-z][a-z0-9_]*)${_b}([a-z][a-z0-9-]*)${_b}(matrices|dual_quats|motors)${_b}([a-z0-9_]+)${_b}([a-z0-9_]+)${_b}([1-4])${_b}([A-Za-z_][A-Za-z0-9_,]*|-)${_b}(${_f}${_b}${_f}${_b}${_f})${_b}([^\"\\]*[^\"\\ \t])[ \t]*$")
      message(FATAL_ERROR "${CGA_SKINNING_METHODS_TABLE}:${_number}: cannot read the row '${_line}' "
                          "(ID NAME PALETTE BONE BLEND VEC4S SPLIT R G B CAPTION; the caption without quotes or backslashes)")
    endif()
    set(_id ${CMAKE_MATCH_1})
    if(_id IN_LIST _ids OR CMAKE_MATCH_2 IN_LIST _names)
      message(FATAL_ERROR "${CGA_SKINNING_METHODS_TABLE}:${_number}: the id ${_id} or the name ${CMAKE_MATCH_2} is taken")
    endif()
    list(APPEND _ids ${_id})
    list(APPEND _names ${CMAKE_MATCH_2})
    set(CGA_SKIN_${_id}_NAME ${CMAKE_MATCH_2} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_PALETTE ${CMAKE_MATCH_3} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_BONE ${CMAKE_MATCH_4} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_BLEND ${CMAKE_MATCH_5} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_VEC4S ${CMAKE_MATCH_6} PARENT_SCOPE)
    set(CGA_SKIN_${_id}_CAPTION "${CMAKE_MATCH_9}" PARENT_SCOPE)
    set(_bone ${CMAKE_MATCH_4})
    set(_blend ${CMAKE_MATCH_5})
    # The blend's batch split (its named values, or none): one per blend script, whichever rows share it.
    set(_split)
    if(NOT CMAKE_MATCH_7 STREQUAL "-")
      string(REPLACE "," ";" _split "${CMAKE_MATCH_7}")
    endif()
    if(DEFINED _split_of_${_blend} AND NOT "${_split_of_${_blend}}" STREQUAL "${_split}")
      message(FATAL_ERROR "${CGA_SKINNING_METHODS_TABLE}:${_number}: method ${_id} splits ${_blend} at '${CMAKE_MATCH_7}', "
                          "another row at '${_split_of_${_blend}}'")
    endif()
    set(_split_of_${_blend} "${_split}")
    set(CGA_SKIN_SPLIT_${_blend} "${_split}" PARENT_SCOPE)
    # (last: a regex command resets CMAKE_MATCH_<n>)
    string(REGEX REPLACE "[ \t]+" ";" _rgb "${CMAKE_MATCH_8}")
    set(CGA_SKIN_${_id}_COLOUR "${_rgb}" PARENT_SCOPE)
    foreach(_script ${_bone} ${_blend})
      if(NOT _script STREQUAL "none" AND NOT EXISTS ${CGA_SKINNING_SCRIPT_DIR}/${_script}.clu)
        message(FATAL_ERROR "${CGA_SKINNING_METHODS_TABLE}:${_number}: method ${_id} names ${_script}, which is not a script in ${CGA_SKINNING_SCRIPT_DIR}")
      endif()
    endforeach()
  endforeach()
  if(NOT _ids)
    message(FATAL_ERROR "${CGA_SKINNING_METHODS_TABLE}: no method rows")
  endif()
  set(CGA_SKINNING_METHOD_IDS ${_ids} PARENT_SCOPE)
  set(CGA_SKINNING_METHOD_NAMES ${_names} PARENT_SCOPE)
endfunction()

# The C++ table (templates/skinning_methods.hpp.in) at <include_dir>/cga/runtime/skinning_methods.hpp. Call
# cga_read_skinning_methods() first. configure_file rewrites it only on a change (no rebuild on re-configure).
function(cga_write_skinning_methods_header include_dir)
  set(CGA_SKINNING_HPP_ROWS)
  set(CGA_SKINNING_HPP_CAPTIONS)
  foreach(_id ${CGA_SKINNING_METHOD_IDS})
    set(_rgb)
    foreach(_c ${CGA_SKIN_${_id}_COLOUR})
      if(NOT _c MATCHES "\\.")
        set(_c "${_c}.0")  # a float literal needs its point: 1f is not C++
      endif()
      list(APPEND _rgb "${_c}f")
    endforeach()
    list(JOIN _rgb ", " _rgb)
    string(APPEND CGA_SKINNING_HPP_ROWS "  X(${_id}, \"${CGA_SKIN_${_id}_NAME}\", ${CGA_SKIN_${_id}_PALETTE}, "
           "${CGA_SKIN_${_id}_BONE}, ${CGA_SKIN_${_id}_BLEND}, ${CGA_SKIN_${_id}_VEC4S}, ${_rgb}) \\\n")
    string(APPEND CGA_SKINNING_HPP_CAPTIONS "  X(${_id}, \"${CGA_SKIN_${_id}_CAPTION}\") \\\n")
  endforeach()
  # The last row ends the macro: no line continuation (and no trailing newline: the template has it).
  string(REGEX REPLACE " \\\\\n$" "" CGA_SKINNING_HPP_ROWS "${CGA_SKINNING_HPP_ROWS}")
  string(REGEX REPLACE " \\\\\n$" "" CGA_SKINNING_HPP_CAPTIONS "${CGA_SKINNING_HPP_CAPTIONS}")
  configure_file(${CGA_SKINNING_TEMPLATE_DIR}/skinning_methods.hpp.in
                 ${include_dir}/cga/runtime/skinning_methods.hpp @ONLY)
endfunction()

# <out> = templates/<name> filled with @VAR@ from the caller's variables (a function sees them); the
# template's own comment lines, those starting with ##, are dropped.
function(cga_skinning_fill_template name out)
  set(_path ${CGA_SKINNING_TEMPLATE_DIR}/${name})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_path})
  file(READ ${_path} _template)
  string(REGEX REPLACE "(^|\n)##[^\n]*" "" _template "${_template}")
  string(REGEX REPLACE "^\n" "" _template "${_template}")
  string(CONFIGURE "${_template}" _text @ONLY)
  set(${out} "${_text}" PARENT_SCOPE)
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
  cga_skinning_glsl_method_skin(${id} METHOD_SKIN)
  set(ID ${id})
  set(VEC4S ${CGA_SKIN_${id}_VEC4S})
  cga_skinning_fill_template(skin_program.glsl.in _text)
  set(${out} "${_text}" PARENT_SCOPE)
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
  list(JOIN _args ",\n      " ARGS)
  set(ID ${id})
  set(NAME ${CGA_SKIN_${id}_NAME})
  set(BLEND ${_blend})
  set(VEC4S ${_k})
  cga_skinning_fill_template(skin_method.glsl.in _text)
  set(${out} "${_text}" PARENT_SCOPE)
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
  list(JOIN _args ",\n      " ARGS)
  set(ID ${id})
  set(NAME ${CGA_SKIN_${id}_NAME})
  set(BLEND ${_blend})
  set(VEC4S ${_k})
  set(READS "${_reads}")
  cga_skinning_fill_template(skin_method.wgsl.in _text)
  set(${out} "${_text}" PARENT_SCOPE)
endfunction()

# The dispatch of either language (lang glsl or wgsl): templates/skin_dispatch.<lang>.in.
function(_cga_skinning_dispatch lang out)
  set(SKINS "")
  set(CASES "")
  set(COUNT 0)
  set(VEC4S_ALL 0)
  foreach(_id ${CGA_SKINNING_METHOD_IDS})
    if(lang STREQUAL "glsl")
      cga_skinning_glsl_method_skin(${_id} _skin)
    else()
      cga_skinning_wgsl_method_skin(${_id} _skin)
    endif()
    # (string(APPEND), not a list: the text holds semicolons)
    string(APPEND CASES "  if (method == ${COUNT}) {\n"
                        "    skin_${_id}(${VEC4S_ALL} * entries, j, w, p, n, op, on);\n    return;\n  }\n")
    string(APPEND SKINS "\n${_skin}")
    math(EXPR COUNT "${COUNT} + 1")
    math(EXPR VEC4S_ALL "${VEC4S_ALL} + ${CGA_SKIN_${_id}_VEC4S}")
  endforeach()
  cga_skinning_fill_template(skin_dispatch.${lang}.in _text)
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
