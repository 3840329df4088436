# A program's --help against the options its doc lists (ctest docs/*_options): every option --help lists
# is in the doc, and every option the doc lists is one --help knows, so neither goes stale alone.
#   cmake -DPROGRAM=path/to/program -DDOC=docs/x.md [-DSECTION="## CLI"] -P option_tables.cmake
# Without SECTION the doc's options are the first column of its option table (rows "| `--opt ...` |"), and
# --help's are the names that begin its option lines ("  --opt ARG   text", "  -O0 | -O1 | -O2   text"),
# compared both ways. With SECTION (a doc that gives the command line as a synopsis in prose) the doc's
# options are those of the section's synopses, the code spans that begin with the program's name
# (`cgagen [--algebra NAME|FILE.csv] ...`); each of --help's option lines must be among them, and each of
# them must be named somewhere in --help (`-v` of `--target list -v` is named in a description).
cmake_minimum_required(VERSION 3.20)
execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE help ERROR_VARIABLE help_err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} --help exited ${rc}: ${help_err}")
endif()
get_filename_component(name ${PROGRAM} NAME)
include(${CMAKE_CURRENT_LIST_DIR}/named_options.cmake)

# --help's option lines: after "options:", lines that begin with two blanks and a '-' (a continuation
# begins with more); each name before the description (alternatives separated by " | ", arguments in
# capitals between).
string(FIND "${help}" "\noptions:\n" at)
if(at LESS 0)
  message(FATAL_ERROR "${PROGRAM} --help has no 'options:' line")
endif()
string(SUBSTRING "${help}" ${at} -1 help_options_text)
string(REPLACE ";" "," help_options_text "${help_options_text}")
string(REGEX REPLACE "[][]" " " help_options_text "${help_options_text}")  # brackets would group list elements
string(REPLACE "\n" ";" help_lines "${help_options_text}")
set(help_options)
foreach(line ${help_lines})
  if(line MATCHES "^  (-.*)$")
    # The names end where two blanks begin the description.
    string(REGEX REPLACE "  .*" "" names "${CMAKE_MATCH_1}")
    string(REGEX MATCHALL "(^| )${option_re}" names "${names}")
    foreach(n ${names})
      string(STRIP "${n}" n)
      list(APPEND help_options ${n})
    endforeach()
  endif()
endforeach()
list(REMOVE_DUPLICATES help_options)
named_options("${help}" help_named)

file(READ ${DOC} doc)
string(REPLACE ";" "," doc "${doc}")
if(DEFINED SECTION)
  string(FIND "${doc}" "\n${SECTION}\n" at)
  if(at LESS 0)
    message(FATAL_ERROR "${DOC} has no section '${SECTION}'")
  endif()
  math(EXPR at "${at} + 1")
  string(SUBSTRING "${doc}" ${at} -1 section)
  string(FIND "${section}" "\n## " next)
  if(next GREATER 0)
    string(SUBSTRING "${section}" 0 ${next} section)
  endif()
  string(REGEX MATCHALL "`${name} [^`]*`" synopses "${section}")
  named_options("${synopses}" doc_options)
  set(known ${help_named})
  set(where "the section '${SECTION}' of ${DOC}")
else()
  string(REPLACE "\n" ";" doc_lines "${doc}")
  set(doc_options)
  foreach(line ${doc_lines})
    if(line MATCHES "^\\| `(${option_re})")
      list(APPEND doc_options ${CMAKE_MATCH_1})
    endif()
  endforeach()
  set(known ${help_options})
  set(where "the option table of ${DOC}")
endif()

list(LENGTH help_options n_help)
list(LENGTH doc_options n_doc)
if(n_help LESS 2 OR n_doc LESS 2)
  message(FATAL_ERROR "found only ${n_help} options in ${name} --help (${help_options}) and ${n_doc} in ${where} "
                      "(${doc_options}): the parsing no longer fits the text")
endif()
set(undocumented)
foreach(o ${help_options})
  if(NOT o IN_LIST doc_options)
    list(APPEND undocumented ${o})
  endif()
endforeach()
set(unknown)
foreach(o ${doc_options})
  if(NOT o IN_LIST known)
    list(APPEND unknown ${o})
  endif()
endforeach()
if(undocumented OR unknown)
  message(FATAL_ERROR "${where} and ${name} --help disagree:\n"
                      "  in --help, not in the doc: ${undocumented}\n  in the doc, not in --help: ${unknown}")
endif()
message(STATUS "${where} and ${name} --help agree on ${n_help} options: ${help_options}")
