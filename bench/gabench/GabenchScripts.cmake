# gabench_kernels(): writes one cgagen script per (model, operation, grade pair) of ga-benchmark's operation
# set, compiles each with cgagen -O2 at build time (no ALL: only when a harness that needs them is built), and
# writes the translation unit that registers the kernels with the harness (bench/gabench/gabench.hpp).
#
#   gabench_kernels(<out_var> MODEL c3ga|e3ga|h3ga OPS <op>... DIR <dir>)
#
# <out_var> receives the registration .cpp. The inputs of each script are general multivectors of one grade
# (every blade of that grade), `#pragma input A ...` (and B); the output is `R`. Each operation's expression
# is what ga-benchmark means by it, which is GATL's definition (its source/GATL/*.hpp): e.g. Inversion of a
# blade is ~A / <A ~A>, and GATL's dual in the conformal model is the opposite of cgagen's `*A`.

set(GABENCH_UNARY_OPS CliffordConjugation Dualization GradeInvolution Inversion Normalization Reversion
    SquaredReverseNorm UnaryMinus UnaryPlus Undualization)
set(GABENCH_BINARY_OPS Addition CommutatorProduct DotProduct GeometricProduct HestenesInnerProduct
    InverseGeometricProduct LeftContraction OuterProduct RegressiveProduct RightContraction ScalarProduct
    Subtraction)

# The model's vectors in cgagen's order and its --algebra argument.
function(_gabench_model model vectors_var algebra_var)
  if(model STREQUAL "c3ga")
    set(${vectors_var} e1 e2 e3 einf e0 PARENT_SCOPE)
    set(${algebra_var} cga PARENT_SCOPE)
  elseif(model STREQUAL "e3ga")
    set(${vectors_var} e1 e2 e3 PARENT_SCOPE)
    set(${algebra_var} 3d PARENT_SCOPE)
  elseif(model STREQUAL "h3ga")
    set(${vectors_var} e1 e2 e3 e4 PARENT_SCOPE)
    set(${algebra_var} ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/h3ga.csv PARENT_SCOPE)
  else()
    message(FATAL_ERROR "gabench: unknown model '${model}' (c3ga e3ga h3ga)")
  endif()
endfunction()

# The blades of grade k over the vectors, in cgagen's order (index tuples in lexicographic order), as
# "e1^e2 e1^e3 ...": bitmask m from 2^n-1 down to 0, the most significant bit being the first vector.
function(_gabench_blades vectors k out_var)
  list(LENGTH vectors n)
  if(k EQUAL 0)
    set(${out_var} "1" PARENT_SCOPE)
    return()
  endif()
  math(EXPR top "(1 << ${n}) - 1")
  set(blades)
  foreach(m RANGE ${top} 0 -1)
    set(names)
    set(count 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE 0 ${last})
      math(EXPR bit "(${m} >> (${n} - 1 - ${i})) & 1")
      if(bit)
        list(GET vectors ${i} v)
        list(APPEND names ${v})
        math(EXPR count "${count} + 1")
      endif()
    endforeach()
    if(count EQUAL k)
      list(JOIN names "^" blade)
      list(APPEND blades ${blade})
    endif()
  endforeach()
  list(JOIN blades " " text)
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# The expression of operation `op` on A (and B) in `model`.
function(_gabench_expression model op out_var)
  set(e_CliffordConjugation "conjugate(A)")
  set(e_GradeInvolution "involute(A)")
  set(e_Inversion "~A / rnorm_sqr(A)")        # GATL's inv: reverse over the squared reverse norm
  set(e_Normalization "normalize(A)")         # A / sqrt(|<A ~A>|), GATL's unit
  set(e_Reversion "~A")
  set(e_SquaredReverseNorm "rnorm_sqr(A)")
  set(e_UnaryMinus "-A")
  set(e_UnaryPlus "+A")
  set(e_Dualization "*A")                     # A I^-1 (lcont(A, I^-1) for the pseudoscalar I)
  set(e_Undualization "undual(A)")            # A I
  set(e_Addition "A + B")
  set(e_CommutatorProduct "cp(A, B)")
  set(e_DotProduct "dot(A, B)")
  set(e_GeometricProduct "A * B")
  set(e_HestenesInnerProduct "hip(A, B)")
  set(e_InverseGeometricProduct "A * (~B / rnorm_sqr(B))")  # GATL's igp: A times inv(B)
  set(e_LeftContraction "lcont(A, B)")
  set(e_OuterProduct "A ^ B")
  # GATL's regressive product is the meet (B* ^ A*) I (the duals in the reverse order of cgagen's rp, which
  # differs by (-1)^((n-a)(n-b)) for grades a, b).
  set(e_RegressiveProduct "rp(B, A)")
  set(e_RightContraction "rcont(A, B)")
  set(e_ScalarProduct "scp(A, B)")
  set(e_Subtraction "A - B")
  if(model STREQUAL "c3ga")
    # GATL's pseudoscalar is e1^e2^e3^no^ni = -(e1^e2^e3^einf^e0): its dual A I^-1 is cgagen's undual and the
    # other way round, and its regressive product (three of those, each with the sign flipped) is -rp(B, A).
    set(e_Dualization "undual(A)")
    set(e_Undualization "*A")
    set(e_RegressiveProduct "-rp(B, A)")
  endif()
  if(NOT DEFINED e_${op})
    message(FATAL_ERROR "gabench: unknown operation '${op}'")
  endif()
  set(${out_var} "${e_${op}}" PARENT_SCOPE)
endfunction()

function(gabench_kernels out_var)
  cmake_parse_arguments(GK "" "MODEL;DIR" "OPS" ${ARGN})
  _gabench_model(${GK_MODEL} vectors algebra)
  list(LENGTH vectors n)
  set(algebra_dep)
  if(algebra MATCHES "\\.csv$")
    set(algebra_dep ${algebra})
  endif()
  if(CGAGEN_EXECUTABLE)
    set(tool ${CGAGEN_EXECUTABLE})
    set(tool_dep ${CGAGEN_EXECUTABLE})
  else()
    set(tool $<TARGET_FILE:cgagen>)
    set(tool_dep cgagen)
  endif()
  set(dir ${GK_DIR}/${GK_MODEL})
  file(MAKE_DIRECTORY ${dir})
  set(includes "")
  set(registrations "")
  set(headers)
  foreach(op ${GK_OPS})
    _gabench_expression(${GK_MODEL} ${op} expr)
    if(op IN_LIST GABENCH_UNARY_OPS)
      set(pairs)
      foreach(ga RANGE 0 ${n})
        list(APPEND pairs "${ga}")
      endforeach()
    elseif(op IN_LIST GABENCH_BINARY_OPS)
      set(pairs)
      foreach(ga RANGE 0 ${n})
        foreach(gb RANGE 0 ${n})
          list(APPEND pairs "${ga}_${gb}")
        endforeach()
      endforeach()
    else()
      message(FATAL_ERROR "gabench: unknown operation '${op}'")
    endif()
    foreach(pair ${pairs})
      set(name ${GK_MODEL}_${op}_${pair})
      string(REPLACE "_" ";" grades "${pair}")
      list(GET grades 0 ga)
      _gabench_blades("${vectors}" ${ga} blades_a)
      string(REPLACE " " ";" list_a "${blades_a}")
      list(LENGTH list_a na)
      set(text "// ga-benchmark's ${op} in ${GK_MODEL}, grade ${pair} (written by bench/gabench/GabenchScripts.cmake)\n")
      string(APPEND text "#pragma input A ${blades_a}\n")
      list(LENGTH grades arity)
      if(arity EQUAL 2)
        list(GET grades 1 gb)
        _gabench_blades("${vectors}" ${gb} blades_b)
        string(APPEND text "#pragma input B ${blades_b}\n")
        string(REPLACE " " ";" list_b "${blades_b}")
        list(LENGTH list_b nb)
        string(APPEND registrations "GABENCH_KERNEL_BINARY(${GK_MODEL}, ${op}, ${ga}, ${gb}, ${na}, ${nb})\n")
      else()
        string(APPEND registrations "GABENCH_KERNEL_UNARY(${GK_MODEL}, ${op}, ${ga}, ${na})\n")
      endif()
      string(APPEND text "?R = ${expr};\n")
      file(CONFIGURE OUTPUT ${dir}/${name}.clu CONTENT "${text}" @ONLY)
      add_custom_command(
        OUTPUT ${dir}/${name}.hpp ${dir}/${name}.stats
        COMMAND ${tool} --target cpp -O2 --name ${name} --algebra ${algebra} --Werror
                --stats-out ${dir}/${name}.stats -o ${dir}/${name}.hpp ${dir}/${name}.clu
        DEPENDS ${dir}/${name}.clu ${tool_dep} ${algebra_dep}
        COMMENT "cgagen ${name}"
        VERBATIM)
      list(APPEND headers ${dir}/${name}.hpp)
      string(APPEND includes "#include \"${GK_MODEL}/${name}.hpp\"\n")
    endforeach()
  endforeach()
  set(cpp ${GK_DIR}/gabench_cgagen_${GK_MODEL}.cpp)
  file(CONFIGURE OUTPUT ${cpp} CONTENT
"// The cgagen kernels of ${GK_MODEL} for gabench, registered with the harness (written by GabenchScripts.cmake).
#include \"cg_side.hpp\"

${includes}
namespace {
using namespace cga::kernels;
${registrations}}  // namespace
" @ONLY)
  set_source_files_properties(${cpp} PROPERTIES OBJECT_DEPENDS "${headers}")
  set(${out_var} ${cpp} PARENT_SCOPE)
endfunction()

# The GATL side of `model` for `ops` (compiled only with GATL_DIR): one translation unit per operation, as
# GATL's templates make each one slow to compile.
function(gabench_gatl_sources out_var)
  cmake_parse_arguments(GG "" "MODEL;DIR" "OPS" ${ARGN})
  set(sources)
  foreach(op ${GG_OPS})
    set(cpp ${GG_DIR}/gabench_gatl_${GG_MODEL}_${op}.cpp)
    if(op IN_LIST GABENCH_UNARY_OPS)
      set(kind UNARY)
    else()
      set(kind BINARY)
    endif()
    file(CONFIGURE OUTPUT ${cpp} CONTENT
"// GATL's ${op} in ${GG_MODEL} for gabench (written by GabenchScripts.cmake; compiled only with GATL_DIR).
#define GABENCH_GATL_MODEL_${GG_MODEL} 1
#include \"gatl_side.hpp\"
GABENCH_GATL_${kind}(${GG_MODEL}, ${op})
" @ONLY)
    list(APPEND sources ${cpp})
  endforeach()
  set(${out_var} ${sources} PARENT_SCOPE)
endfunction()
