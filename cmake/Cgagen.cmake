# cgagen_generate(): run the cgagen tool on CluScript files at build time.
#
#   cgagen_generate(<target>
#                   SCRIPTS a.clu [b.clu ...]
#                   [LIBRARIES a.gal ...]        # library specs (cgagen --library, docs/library.md): each
#                                               # a.gal -> OUTPUT_DIR/A<ext> per target (SCRIPTS optional)
#                   OUTPUT_DIR <dir>
#                   [TARGETS cpp glsl ...]      # default: cpp; any of cmake/CgagenTargets.cmake
#                   [OPT -O2]                   # default: -O2
#                   [ALGEBRA name|file.csv]     # default: cga; --algebra (2d 3d 2dpga 3dpga cra sta gac qga dcga
#                                               # ccga, or a Gaalop definition.csv, a dependency then)
#                   [PACK NAME=KIND ...]        # glsl only: --pack NAME=KIND (mat3x4, vec4, vec3, float)
#                   [RETURN OUT]                # glsl only: --return OUT
#                   [UNIFORM NAME ...]          # --uniform: stage the kernels (NAME_prepare + NAME)
#                   [STAGE_AT VALUE ...]        # --stage-at: stage them at these named values of the scripts
#                   [OUTPUTS NAME ...]          # --outputs: only these outputs of the scripts
#                   [NAME name]                 # --name: the kernel's (and the files') name instead of the
#                                               # script's stem; one script only (e.g. a staged second copy)
#                   [TEMPLATES <dir>]           # default: the tool's built-in templates/
#                   [GPC_TYPE float|double]     # GPC sources: --type, the blocks' number type (default float)
#                   [NO_WERROR])                # warnings stay warnings (default: --Werror, so a misspelt
#                                               # name that silently became an input fails the build)
#
# For each script NAME.clu and each target it writes OUTPUT_DIR/NAME<ext> (.hpp, .glsl, .cuh, .py, ...: the
# target's extension from cmake/CgagenTargets.cmake, the table `cgagen --target list` prints; NAME: the stem
# as an identifier, `my-kernel.clu` -> my_kernel, `2pga.clu` -> _2pga, also the function's name), plus
# OUTPUT_DIR/NAME.stats (the --stats text), with dependencies on the script, the templates and the cgagen
# tool. <target> is an INTERFACE library whose include directory is OUTPUT_DIR; linking it builds the files
# first. A GPC source (C/C++/CUDA with `#pragma gpc` blocks, docs/gpc.md) is recognised by its name:
# NAME.hpg -> OUTPUT_DIR/NAME.hpp, NAME.cpg -> NAME.cpp, NAME.gpc.EXT -> NAME.EXT (NAME.gpc.cu -> NAME.cu);
# it is rewritten once by `cgagen --gpc` with the first of TARGETS (cpp, cuda or opencl), OPT, ALGEBRA and
# GPC_TYPE, its `#line` directives naming the source's absolute path. Call it several times with the same <target> to give scripts different options (packing differs
# per script); the files of every call are listed in the target's CGAGEN_OUTPUTS property.
# The tool is CGAGEN_EXECUTABLE when set, else the target `cgagen` (this project), else the imported
# `cgagen::cgagen` of an installed cgagen (find_package(cgagen), which includes this file from
# <prefix>/share/cgagen/cmake; the default templates are then <prefix>/share/cgagen/templates).

include(${CMAKE_CURRENT_LIST_DIR}/CgagenTargets.cmake)
set(CGAGEN_DEFAULT_TEMPLATES "${CMAKE_CURRENT_LIST_DIR}/../templates" CACHE PATH "Templates of cgagen_generate()")

function(cgagen_generate target)
  cmake_parse_arguments(CG "NO_WERROR" "OUTPUT_DIR;OPT;RETURN;TEMPLATES;ALGEBRA;NAME;GPC_TYPE" "SCRIPTS;TARGETS;PACK;UNIFORM;STAGE_AT;OUTPUTS;LIBRARIES"
                        ${ARGN})
  if(CG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "cgagen_generate(${target}): unknown arguments ${CG_UNPARSED_ARGUMENTS}")
  endif()
  if((NOT CG_SCRIPTS AND NOT CG_LIBRARIES) OR NOT CG_OUTPUT_DIR)
    message(FATAL_ERROR "cgagen_generate(${target}): SCRIPTS or LIBRARIES, and OUTPUT_DIR, are required")
  endif()
  if(CG_NAME)
    list(LENGTH CG_SCRIPTS _n_scripts)
    if(NOT _n_scripts EQUAL 1)
      message(FATAL_ERROR "cgagen_generate(${target}): NAME ${CG_NAME} needs exactly one script (got ${CG_SCRIPTS})")
    endif()
  endif()
  if(NOT CG_TARGETS)
    set(CG_TARGETS cpp)
  endif()
  if(NOT CG_OPT)
    set(CG_OPT -O2)
  endif()
  if(CG_TEMPLATES)
    set(_templates_dir ${CG_TEMPLATES})
    set(_templates_arg --templates ${CG_TEMPLATES})
  else()
    get_filename_component(_templates_dir ${CGAGEN_DEFAULT_TEMPLATES} ABSOLUTE)
    set(_templates_arg)
  endif()
  file(GLOB_RECURSE _templates CONFIGURE_DEPENDS ${_templates_dir}/*.in)
  if(CGAGEN_EXECUTABLE)
    set(_tool ${CGAGEN_EXECUTABLE})
    set(_tool_dep ${CGAGEN_EXECUTABLE})
  elseif(TARGET cgagen)
    set(_tool $<TARGET_FILE:cgagen>)
    set(_tool_dep cgagen)
  elseif(TARGET cgagen::cgagen)
    set(_tool $<TARGET_FILE:cgagen::cgagen>)
    set(_tool_dep $<TARGET_FILE:cgagen::cgagen>)
  else()
    message(FATAL_ERROR "cgagen_generate(${target}): no cgagen: find_package(cgagen) or set CGAGEN_EXECUTABLE")
  endif()
  set(_glsl_args)
  foreach(_p ${CG_PACK})
    list(APPEND _glsl_args --pack ${_p})
  endforeach()
  # Not if(CG_RETURN): an output named N, Y, NO or OFF reads as false there.
  if(NOT "${CG_RETURN}" STREQUAL "")
    list(APPEND _glsl_args --return ${CG_RETURN})
  endif()

  # ALGEBRA: a built-in name is passed as is; anything else is a definition file the outputs depend on.
  set(_algebra_args)
  set(_algebra_dep)
  if(CG_ALGEBRA)
    set(_builtin_algebras 2d 3d 2dpga 3dpga cra sta cga gac qga dcga ccga)
    if(CG_ALGEBRA IN_LIST _builtin_algebras)
      set(_algebra_args --algebra ${CG_ALGEBRA})
    else()
      get_filename_component(_algebra_file ${CG_ALGEBRA} ABSOLUTE)
      set(_algebra_args --algebra ${_algebra_file})
      set(_algebra_dep ${_algebra_file})
    endif()
  endif()

  file(MAKE_DIRECTORY ${CG_OUTPUT_DIR})
  set(_outputs)
  foreach(_script ${CG_SCRIPTS})
    get_filename_component(_script ${_script} ABSOLUTE)
    # A GPC source: one rewritten file, named after the source (see the top of this file).
    get_filename_component(_file ${_script} NAME)
    set(_gpc_out)
    if(_file MATCHES "^(.+)\\.hpg$")
      set(_gpc_out ${CMAKE_MATCH_1}.hpp)
    elseif(_file MATCHES "^(.+)\\.cpg$")
      set(_gpc_out ${CMAKE_MATCH_1}.cpp)
    elseif(_file MATCHES "^(.+)\\.gpc(\\.[^.]+)$")
      set(_gpc_out ${CMAKE_MATCH_1}${CMAKE_MATCH_2})
    endif()
    if(_gpc_out)
      list(GET CG_TARGETS 0 _t)
      if(NOT _t MATCHES "^(cpp|cuda|opencl)$" OR CG_UNIFORM OR CG_STAGE_AT OR CG_OUTPUTS OR CG_NAME OR CG_PACK OR CG_RETURN)
        message(FATAL_ERROR "cgagen_generate(${target}): the GPC source ${_file} takes TARGETS cpp, cuda or opencl, "
                            "OPT, ALGEBRA, GPC_TYPE and NO_WERROR only")
      endif()
      set(_args --gpc --target ${_t} ${CG_OPT} ${_templates_arg} ${_algebra_args})
      if(CG_GPC_TYPE)
        list(APPEND _args --type ${CG_GPC_TYPE})
      endif()
      if(NOT CG_NO_WERROR)
        list(APPEND _args --Werror)
      endif()
      add_custom_command(
        OUTPUT ${CG_OUTPUT_DIR}/${_gpc_out}
        COMMAND ${_tool} ${_args} -o ${CG_OUTPUT_DIR}/${_gpc_out} ${_script}
        DEPENDS ${_script} ${_tool_dep} ${_algebra_dep}
        COMMENT "cgagen --gpc ${_gpc_out}"
        VERBATIM)
      list(APPEND _outputs ${CG_OUTPUT_DIR}/${_gpc_out})
      continue()
    endif()
    # The function and file name: the stem as cgagen spells it (a byte other than a letter, digit or _
    # becomes _, a leading digit gets a _ in front: my-kernel.clu -> my_kernel.hpp, my_kernel()).
    get_filename_component(_name ${_script} NAME_WE)
    string(MAKE_C_IDENTIFIER "${_name}" _name)
    if(CG_NAME)
      set(_name ${CG_NAME})
    endif()
    set(_stats_done OFF)
    foreach(_t ${CG_TARGETS})
      if(NOT DEFINED CGAGEN_EXT_${_t})
        message(FATAL_ERROR "cgagen_generate(${target}): unknown target '${_t}' (${CGAGEN_TARGETS})")
      endif()
      set(_ext ${CGAGEN_EXT_${_t}})
      set(_out ${CG_OUTPUT_DIR}/${_name}${_ext})
      set(_args --target ${_t} ${CG_OPT} --name ${_name} ${_templates_arg} ${_algebra_args})
      if(CG_UNIFORM)
        list(JOIN CG_UNIFORM "," _uniform)
        list(APPEND _args --uniform ${_uniform})
      endif()
      if(CG_STAGE_AT)
        list(JOIN CG_STAGE_AT "," _stage_at)
        list(APPEND _args --stage-at ${_stage_at})
      endif()
      if(CG_OUTPUTS)
        list(JOIN CG_OUTPUTS "," _kept)
        list(APPEND _args --outputs ${_kept})
      endif()
      if(NOT CG_NO_WERROR)
        list(APPEND _args --Werror)
      endif()
      if(_t STREQUAL "glsl" OR _t STREQUAL "glsl-es")
        list(APPEND _args ${_glsl_args})
      endif()
      set(_byproducts ${_out})
      if(NOT _stats_done)
        list(APPEND _args --stats-out ${CG_OUTPUT_DIR}/${_name}.stats)
        list(APPEND _byproducts ${CG_OUTPUT_DIR}/${_name}.stats)
        set(_stats_done ON)
      endif()
      add_custom_command(
        OUTPUT ${_byproducts}
        COMMAND ${_tool} ${_args} -o ${_out} ${_script}
        DEPENDS ${_script} ${_templates} ${_tool_dep} ${_algebra_dep}
        COMMENT "cgagen ${_name}${_ext}"
        VERBATIM)
      list(APPEND _outputs ${_byproducts})
    endforeach()
  endforeach()

  # Library specs: one file per target, named after the spec's stem (the spec names its namespace). One cgagen
  # run per spec writes every target (--also): the functions are built and optimized once.
  foreach(_spec ${CG_LIBRARIES})
    get_filename_component(_spec ${_spec} ABSOLUTE)
    get_filename_component(_name ${_spec} NAME_WE)
    string(MAKE_C_IDENTIFIER "${_name}" _name)
    set(_lib_outs "")
    set(_lib_args "")
    foreach(_t ${CG_TARGETS})
      if(NOT DEFINED CGAGEN_EXT_${_t})
        message(FATAL_ERROR "cgagen_generate(${target}): unknown target '${_t}' (${CGAGEN_TARGETS})")
      endif()
      set(_out ${CG_OUTPUT_DIR}/${_name}${CGAGEN_EXT_${_t}})
      if(_lib_outs)
        list(APPEND _lib_args --also ${_t}=${_out})
      else()
        list(APPEND _lib_args --target ${_t} -o ${_out})
      endif()
      list(APPEND _lib_outs ${_out})
    endforeach()
    list(JOIN CG_TARGETS "," _lib_targets)
    add_custom_command(
      OUTPUT ${_lib_outs}
      COMMAND ${_tool} --library ${CG_OPT} ${_templates_arg} ${_lib_args} ${_spec}
      DEPENDS ${_spec} ${_templates} ${_tool_dep}
      COMMENT "cgagen --library ${_name} (${_lib_targets})"
      VERBATIM)
    list(APPEND _outputs ${_lib_outs})
  endforeach()

  get_property(_calls GLOBAL PROPERTY CGAGEN_CALLS_${target})
  if(NOT _calls)
    set(_calls 0)
  endif()
  math(EXPR _calls "${_calls} + 1")
  set_property(GLOBAL PROPERTY CGAGEN_CALLS_${target} ${_calls})
  add_custom_target(${target}_files_${_calls} ALL DEPENDS ${_outputs})
  if(NOT TARGET ${target})
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE $<BUILD_INTERFACE:${CG_OUTPUT_DIR}>)
    target_compile_features(${target} INTERFACE cxx_std_17)
  endif()
  add_dependencies(${target} ${target}_files_${_calls})
  set_property(TARGET ${target} APPEND PROPERTY CGAGEN_OUTPUTS ${_outputs})
  set_property(TARGET ${target} APPEND PROPERTY CGAGEN_FILE_TARGETS ${target}_files_${_calls})
endfunction()
