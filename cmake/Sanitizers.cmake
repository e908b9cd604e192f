# Sanitizer and fuzzing builds (README, "Tests"; hdHair/fuzz/README.md).
#
#   -DHDHAIR_SANITIZE=ON   AddressSanitizer and UndefinedBehaviorSanitizer on
#                          everything hdHair compiles (its tests then run under
#                          them, with the default options and Mesa's leak
#                          suppressions compiled in from
#                          cmake/sanitizers/SanitizerDefaults.cpp).
#   -DHDHAIR_FUZZ=ON       libFuzzer targets in hdHair/fuzz (needs clang;
#                          implies the sanitizers), with coverage on the code
#                          they reach.
option(HDHAIR_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(HDHAIR_FUZZ "Build the libFuzzer targets (clang)" OFF)
if(HDHAIR_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "hdHair: HDHAIR_FUZZ needs clang (configure with CC=clang CXX=clang++); "
                        "libFuzzer is part of clang (Debian: clang, libclang-rt-14-dev)")
  endif()
  set(HDHAIR_SANITIZE ON)
endif()
if(HDHAIR_SANITIZE)
  set(_hdhair_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  if(HDHAIR_FUZZ)
    # Coverage for the fuzzers everywhere; the fuzz targets add libFuzzer's main.
    list(APPEND _hdhair_sanitizers -fsanitize=fuzzer-no-link)
  endif()
  add_compile_options(${_hdhair_sanitizers})
  add_link_options(-fsanitize=address,undefined)
  # Every target created from here on links the defaults' object file.
  add_library(hdhair_sanitizer_defaults OBJECT ${CMAKE_CURRENT_LIST_DIR}/sanitizers/SanitizerDefaults.cpp)
  link_libraries(hdhair_sanitizer_defaults)
  message(STATUS "hdHair: AddressSanitizer and UndefinedBehaviorSanitizer on")
endif()
