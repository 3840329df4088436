# Test generated_up_to_date: each freshly generated file (FRESH_DIR) must equal its checked-in copy
# (CHECKED_DIR) byte for byte. Run as: cmake -DFRESH_DIR=... -DCHECKED_DIR=... -DFILES=a;b -P compare.cmake
if(NOT FILES)
  message(FATAL_ERROR "generated_up_to_date: no generated files listed")
endif()
foreach(_f ${FILES})
  if(NOT EXISTS ${FRESH_DIR}/${_f})
    message(FATAL_ERROR "generated_up_to_date: ${FRESH_DIR}/${_f} was not generated (build first)")
  endif()
  if(NOT EXISTS ${CHECKED_DIR}/${_f})
    message(FATAL_ERROR "generated_up_to_date: generated/${_f} is not checked in; "
                        "run: cmake --build build --target cgagen-update")
  endif()
  file(READ ${FRESH_DIR}/${_f} _fresh HEX)
  file(READ ${CHECKED_DIR}/${_f} _checked HEX)
  if(NOT _fresh STREQUAL _checked)
    message(FATAL_ERROR "generated_up_to_date: generated/${_f} differs from a fresh regeneration "
                        "(${FRESH_DIR}/${_f}); run: cmake --build build --target cgagen-update")
  endif()
endforeach()
message(STATUS "generated_up_to_date: ${FILES} match")
