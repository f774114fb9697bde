# kautham_set_warnings(<target>): the warning flags every target of the project builds with.
function(kautham_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
  if(KAUTHAM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
