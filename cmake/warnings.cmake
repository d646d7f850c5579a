# meshdev_set_warnings(<target>): the project's warning set, per target (no global flags).
function(meshdev_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(MESHDEV_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
