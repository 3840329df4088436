# cmake -DGLSLANG=glslangValidator -DLIBRARY=lib.essl -DOUT=x.frag -P glsl_es_compile.cmake: compiles a generated
# GLSL ES library (cgagen --library --target glsl-es) as a GLSL ES 3.00 fragment shader (WebGL 2's version):
# the #version line, the library, and an empty main. Fails on any error or warning of glslangValidator.
file(READ ${LIBRARY} _library)
file(WRITE ${OUT} "#version 300 es\n${_library}\nout highp vec4 fragment;\nvoid main() { fragment = vec4(0.0); }\n")
execute_process(COMMAND ${GLSLANG} ${OUT} RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
if(NOT _rc EQUAL 0 OR _out MATCHES "WARNING|ERROR")
  message(FATAL_ERROR "glslangValidator ${OUT} (${_rc}):\n${_out}")
endif()
