# Warnings for our own targets only (generated and third-party code is left alone).
add_library(ubersim_warnings INTERFACE)
target_compile_options(ubersim_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
if(UBERSIM_WERROR)
  target_compile_options(ubersim_warnings INTERFACE -Werror)
endif()
option(UBERSIM_WERROR "Treat warnings as errors" OFF)
