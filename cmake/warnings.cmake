# SPDX-License-Identifier: MIT
function(runnel_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(RUNNEL_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
