# Warnings every mimic target compiles with.
add_library(mimic_warnings INTERFACE)
target_compile_options(mimic_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Woverloaded-virtual -Wconversion -Wsign-conversion -Wnull-dereference -Wdouble-promotion
  -Wformat=2 -Wimplicit-fallthrough)
if(MIMIC_WERROR)
  target_compile_options(mimic_warnings INTERFACE -Werror)
endif()
