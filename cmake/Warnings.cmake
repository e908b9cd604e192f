# Warnings on for every hdHair target; -Werror when HDHAIR_WERROR is set (CI).
add_library(hdhair_warnings INTERFACE)
target_compile_options(hdhair_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual>
  $<$<BOOL:${HDHAIR_WERROR}>:-Werror>)
