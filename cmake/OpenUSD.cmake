# OpenUSD is optional: the Hydra plugin (hdHair/hydra) and hdhair-record's
# --reader usd are built only when it is found (HDHAIR_HYDRA = AUTO, ON or
# OFF). It is never a Debian package: point CMake at a build of OpenUSD 24.08
# with -Dpxr_DIR=<prefix> or CMAKE_PREFIX_PATH (README, "Hydra plugin").
set(HDHAIR_HYDRA AUTO CACHE STRING "Build the Hydra plugin: AUTO (when OpenUSD is found), ON (required), OFF")
set_property(CACHE HDHAIR_HYDRA PROPERTY STRINGS AUTO ON OFF)
set(HDHAIR_WITH_USD OFF)
if(HDHAIR_HYDRA STREQUAL "OFF")
  message(STATUS "hdHair: Hydra plugin off (HDHAIR_HYDRA=OFF)")
  return()
endif()
# pxrConfig.cmake re-finds the Python OpenUSD was built with (an exact
# version) but only hints its interpreter, so FindPython3 can still take the
# headers of another Python first on PATH (pyenv, a virtualenv) and fail.
# Search under the recorded interpreter's prefix unless told otherwise.
if(NOT DEFINED Python3_ROOT_DIR)
  find_file(_hdhair_pxr_config pxrConfig.cmake
            PATHS ${pxr_DIR} $ENV{pxr_DIR} ${PXR_ROOT} $ENV{PXR_ROOT} ${CMAKE_PREFIX_PATH} NO_DEFAULT_PATH)
  if(_hdhair_pxr_config)
    file(STRINGS "${_hdhair_pxr_config}" _hdhair_pxr_python REGEX "set\\(Python3_EXECUTABLE \\[\\[.+\\]\\]\\)")
    if(_hdhair_pxr_python MATCHES "\\[\\[(.+)/bin/[^/]+\\]\\]")
      set(Python3_ROOT_DIR "${CMAKE_MATCH_1}")
      message(STATUS "hdHair: OpenUSD was built with ${CMAKE_MATCH_1}'s Python; looking for its headers there")
    endif()
  endif()
  unset(_hdhair_pxr_config CACHE)
endif()
find_package(pxr CONFIG QUIET PATHS ${PXR_ROOT} $ENV{PXR_ROOT})
if(NOT pxr_FOUND)
  if(HDHAIR_HYDRA STREQUAL "ON")
    message(FATAL_ERROR "hdHair: HDHAIR_HYDRA=ON but OpenUSD was not found. Point CMake at an OpenUSD "
                        "24.08 install with -Dpxr_DIR=<prefix> or -DCMAKE_PREFIX_PATH=<prefix> (the folder "
                        "holding pxrConfig.cmake), or use HDHAIR_HYDRA=AUTO to build without the plugin.")
  endif()
  message(STATUS "hdHair: OpenUSD not found, the Hydra plugin is not built (set pxr_DIR to build it)")
  return()
endif()
message(STATUS "hdHair: building the Hydra plugin against OpenUSD ${PXR_VERSION} (${pxr_DIR})")
set(HDHAIR_WITH_USD ON)

# A monolithic OpenUSD build exports one library, usd_ms; a per-library
# build exports each (imported targets without a namespace).
if(TARGET usd_ms)
  # OpenUSD 24.08 exports usd_ms without include directories, nor the
  # Python headers its own headers need when it was built with Python (the
  # per-library targets carry both): add them.
  get_target_property(_hdhair_pxr_includes usd_ms INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT _hdhair_pxr_includes)
    set(_hdhair_pxr_includes ${PXR_INCLUDE_DIRS})
    file(READ "${PXR_INCLUDE_DIRS}/pxr/pxr.h" _hdhair_pxr_h)
    if(_hdhair_pxr_h MATCHES "#if 1[ \t\r\n]+#define PXR_PYTHON_SUPPORT_ENABLED")
      find_package(Python3 REQUIRED COMPONENTS Development)
      list(APPEND _hdhair_pxr_includes ${Python3_INCLUDE_DIRS})
    endif()
    set_target_properties(usd_ms PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_hdhair_pxr_includes}")
  endif()
  set(HDHAIR_PXR_IMAGING usd_ms)
  set(HDHAIR_PXR_USDIMAGING usd_ms)
  set(HDHAIR_PXR_USDLUX usd_ms)
else()
  set(HDHAIR_PXR_IMAGING hd hf cameraUtil gf vt tf sdf plug work trace)
  set(HDHAIR_PXR_USDIMAGING usdImagingGL usdImaging usdGeom usd hdx ${HDHAIR_PXR_IMAGING})
  set(HDHAIR_PXR_USDLUX usdLux)
endif()
get_filename_component(HDHAIR_PXR_LIBRARY_DIR "${PXR_INCLUDE_DIRS}/../lib" ABSOLUTE)
get_filename_component(HDHAIR_PXR_BIN "${PXR_INCLUDE_DIRS}/../bin" ABSOLUTE)
# OpenUSD's Python modules, which its tools (usdrecord, usdview: Python
# scripts) import. C++ tests put them on the commands they run; Python tests
# get HDHAIR_PXR_TEST_ENVIRONMENT from CTest. Either way ctest works without
# the caller setting PYTHONPATH.
get_filename_component(HDHAIR_PXR_PYTHONPATH "${PXR_INCLUDE_DIRS}/../lib/python" ABSOLUTE)
set(HDHAIR_PXR_TEST_ENVIRONMENT "PYTHONPATH=${HDHAIR_PXR_PYTHONPATH}")
# Where the plugin's plugInfo.json lands in the build tree.
set(HDHAIR_PLUGIN_RESOURCES ${CMAKE_BINARY_DIR}/plugin/usd/hdHair/resources)
