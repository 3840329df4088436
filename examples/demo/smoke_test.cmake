# ctest driver for cga-demo (cmake -P): runs the demo on its default character with few frames and fails
# unless it exits 0, prints every table, skins on the GL path within 1e-4 of the character's size for every
# method and path, and writes every picture, each CPU picture the same size as its GPU twin (they share pose,
# camera and caption band) and differing from it in at most 1 % of its pixels. Variables: DEMO (the
# executable), OUT (a scratch folder).
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${DEMO}" --frames 4 --out "${OUT}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cga-demo exited with ${rc}\n${out}\n${err}")
endif()
foreach(want "us/pose" "Mvertices/s" "cga-points vs lbs" "middle ring radius" "GPU skinning of the mid-fade pose")
  string(FIND "${out}" "${want}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "cga-demo printed no '${want}'\n${out}")
  endif()
endforeach()
# The GL table: one row per method, two cells "DEVIATION (T ms)"; a deviation of 1e-4 or more fails.
foreach(method lbs dqs cga-points cga-motors)
  if(NOT out MATCHES "\n  ${method} +([0-9.e+-]+) \\([0-9.]+ ms\\) +([0-9.e+-]+) \\([0-9.]+ ms\\)\n")
    message(FATAL_ERROR "no GPU row for ${method}\n${out}")
  endif()
  foreach(value "${CMAKE_MATCH_1}" "${CMAKE_MATCH_2}")
    if(NOT value MATCHES "^(0|[0-9.]+e-(0[5-9]|[1-9][0-9]))$")
      message(FATAL_ERROR "GPU skinning of ${method} is ${value} of the size away from the CPU job\n${out}")
    endif()
  endforeach()
endforeach()
# IK (ik_demo.cpp): the right hand within 1e-4 of the arm length of its target (the demo also fails itself).
if(NOT out MATCHES "IK: right hand reaches the target [^\n]*: distance ([0-9.e+-]+) of the arm length")
  message(FATAL_ERROR "cga-demo printed no IK line\n${out}")
endif()
if(NOT CMAKE_MATCH_1 MATCHES "^(0|[0-9.]+e-(0[5-9]|[1-9][0-9]))$")
  message(FATAL_ERROR "the IK hand is ${CMAKE_MATCH_1} of the arm length from its target\n${out}")
endif()
foreach(png ik-hand-reach character-lbs character-dqs character-cga-points character-cga-motors twist-strip
            gpu-character-lbs gpu-character-dqs gpu-character-cga-points gpu-character-cga-motors gpu-twist-strip)
  if(NOT EXISTS "${OUT}/${png}.png")
    message(FATAL_ERROR "cga-demo wrote no ${OUT}/${png}.png\n${out}")
  endif()
endforeach()
# A PNG's width and height are the 8 bytes after its signature and IHDR header (offset 16).
foreach(png character-lbs character-dqs character-cga-points character-cga-motors twist-strip)
  file(READ "${OUT}/${png}.png" cpu_size OFFSET 16 LIMIT 8 HEX)
  file(READ "${OUT}/gpu-${png}.png" gpu_size OFFSET 16 LIMIT 8 HEX)
  if(NOT cpu_size STREQUAL gpu_size)
    message(FATAL_ERROR "${png}.png (${cpu_size}) and gpu-${png}.png (${gpu_size}) differ in size")
  endif()
endforeach()
# The demo's own comparison of each GPU picture with its CPU twin (pictures.cpp): at most 1 % of the pixels
# differ by more than 16/255 (a different pose, framing or shading differs in far more).
if(NOT out MATCHES "pictures, GPU against CPU: pixels that differ by more than 16/255: ([^\n]*)")
  message(FATAL_ERROR "cga-demo printed no GPU-against-CPU picture comparison\n${out}")
endif()
set(compared "${CMAKE_MATCH_1}")
foreach(png character-lbs character-dqs character-cga-points character-cga-motors twist-strip)
  if(NOT compared MATCHES "${png} ([0-9]+) of ([0-9]+)")
    message(FATAL_ERROR "no comparison for ${png}: ${compared}")
  endif()
  math(EXPR limit "${CMAKE_MATCH_2} / 100")
  if(CMAKE_MATCH_1 GREATER limit)
    message(FATAL_ERROR "gpu-${png}.png differs from ${png}.png in ${CMAKE_MATCH_1} of ${CMAKE_MATCH_2} pixels")
  endif()
endforeach()
