# cmake -DKIND=essl|hlsl|cl|wgsl -DTOOL=... -DLIBRARY=pga3.EXT -DSNIPPET=turn.EXT -DOUT=base [-DPYTHON=python3
# -DTARGETS_DIR=tests/targets] -P check.cmake: puts a generated library and the example's use of it into one
# shader or program, as a user would (WGSL has no #include, so this pastes for every target alike), and
# compiles it with the target's toolchain. essl: glslangValidator as a GLSL ES 3.00 fragment shader (WebGL 2);
# hlsl: glslangValidator -D to SPIR-V; cl: clang -x cl -cl-std=CL1.2; all with warnings as errors. wgsl: runs
# it in headless Chromium's WebGPU through tests/targets' harness (TOOL is chromium-headless-shell), where the
# shader writes 1.0 when its turned point is right: the harness's output row must be 1.0f (base64 AACAPw==).
file(READ ${LIBRARY} _library)
file(READ ${SNIPPET} _snippet)
if(KIND STREQUAL "essl")
  file(WRITE ${OUT}.frag "#version 300 es\n${_library}\n${_snippet}")
  set(_cmd ${TOOL} ${OUT}.frag)
elseif(KIND STREQUAL "hlsl")
  file(WRITE ${OUT}.hlsl "${_library}\n${_snippet}")
  set(_cmd ${TOOL} -D -V -S comp -e main -o ${OUT}.spv ${OUT}.hlsl)
elseif(KIND STREQUAL "cl")
  file(WRITE ${OUT}.cl "${_library}\n${_snippet}")
  set(_cmd ${TOOL} -x cl -cl-std=CL1.2 -Xclang -finclude-default-header -fsyntax-only -Wall -Werror ${OUT}.cl)
elseif(KIND STREQUAL "wgsl")
  # The code rides in a text/wgsl script element (only "</script" could end it): no escaping into a JS string.
  # The one input is the angle, 0.7f (base64 MzMzPw==).
  file(READ ${TARGETS_DIR}/browser_harness.js _harness)
  file(WRITE ${OUT}.html "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>pga3 in WGSL</title></head><body>\n"
             "<script type=\"text/wgsl\" id=\"wgsl\">\n${_library}\n${_snippet}</script>\n<script>\n"
             "const CGAGEN_API = \"webgpu\";\nconst CGAGEN_CASES = [{name: \"turn\", rows: 1, nin: 1, nout: 1, "
             "input: \"MzMzPw==\", code: document.getElementById(\"wgsl\").textContent}];\n</script>\n"
             "<script>\n${_harness}</script>\n</body></html>\n")
  set(_cmd ${PYTHON} ${TARGETS_DIR}/browser_run.py ${TOOL} webgpu ${OUT}.html ${OUT}.txt 120)
else()
  message(FATAL_ERROR "check.cmake: KIND must be essl, hlsl, cl or wgsl, not '${KIND}'")
endif()
execute_process(COMMAND ${_cmd} RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
if(NOT _rc EQUAL 0 OR (NOT KIND STREQUAL "wgsl" AND _out MATCHES "WARNING|ERROR|warning|error"))
  message(FATAL_ERROR "${_cmd} (${_rc}):\n${_out}")
endif()
if(KIND STREQUAL "wgsl")
  file(READ ${OUT}.txt _result)
  if(NOT _result MATCHES "\ncase turn [0-9.]+ [0-9.]+ AACAPw==\n")
    message(FATAL_ERROR "pga3 in WGSL: the turned point is wrong or the shader failed (${OUT}.html):\n${_result}")
  endif()
  message(STATUS "pga3 in WGSL (headless Chromium, WebGPU on SwiftShader): the turned point agrees")
else()
  message(STATUS "pga3 + ${SNIPPET}: compiled without a warning")
endif()
