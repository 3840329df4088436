# named_options(TEXT OUT): every option (-x, --long-name) named anywhere in TEXT, after a blank, a bracket, a
# bar, a comma, a quote, a slash or a line start; each once. Shared by the doc checks against --help
# (tests/docs/option_tables.cmake, tests/install/man_page.cmake).
set(option_re "--?[A-Za-z][A-Za-z0-9-]*")
function(named_options text out)
  # Square brackets would group CMake list elements: blanks instead.
  string(REGEX REPLACE "[][]" " " text "${text}")
  string(REGEX MATCHALL "(^|[ \n|(,`\"'/])${option_re}" tokens "${text}")
  set(found)
  foreach(t ${tokens})
    string(REGEX REPLACE "^[^-]+" "" t "${t}")
    list(APPEND found ${t})
  endforeach()
  list(REMOVE_DUPLICATES found)
  set(${out} ${found} PARENT_SCOPE)
endfunction()
