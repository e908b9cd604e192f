# Every dependency comes from a Debian 12 package; README.md lists which and why.
find_package(Threads REQUIRED)
find_package(glm REQUIRED)                        # libglm-dev
find_package(TBB REQUIRED)                        # libtbb-dev
find_package(fmt REQUIRED)                        # libfmt-dev
find_package(CLI11 REQUIRED)                      # libcli11-dev
find_package(nlohmann_json REQUIRED)              # nlohmann-json3-dev
find_package(OpenImageIO REQUIRED)                # libopenimageio-dev
# Debian 12's OpenImageIOTargets.cmake lists /usr/include/opencv4 even when
# OpenCV is not installed (hdHair does not use OpenCV); drop include folders
# that do not exist instead of installing OpenCV to satisfy the package.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
set(_oiio_existing_includes)
foreach(_dir IN LISTS _oiio_includes)
  if(EXISTS "${_dir}")
    list(APPEND _oiio_existing_includes "${_dir}")
  endif()
endforeach()
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${_oiio_existing_includes}")
find_package(OpenEXR REQUIRED)                    # libopenexr-dev
# OpenColorIO through pkg-config: Debian 12 moved OpenColorIOConfig.cmake to
# /usr/share/cmake without its relocation, so its imported target points at
# /include (a broken package config, as OpenImageIO's above).
find_package(PkgConfig REQUIRED)                  # pkg-config
pkg_check_modules(OpenColorIO REQUIRED IMPORTED_TARGET OpenColorIO>=2.1)  # libopencolorio-dev
find_package(OpenGL REQUIRED COMPONENTS EGL)      # libegl-dev
find_library(OSMESA_LIBRARY NAMES OSMesa REQUIRED) # libosmesa6-dev
find_path(OSMESA_INCLUDE_DIR GL/osmesa.h REQUIRED)
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED) # glslang-tools
# libosd-dev: OpenSubdiv refines meshes on the CPU (Far only). Debian 12's
# OpenSubdivConfig.cmake lists static libraries the package does not ship,
# so find_package(OpenSubdiv) fails there: the CPU library and the headers
# are found directly.
find_library(OPENSUBDIV_CPU_LIBRARY NAMES osdCPU REQUIRED)
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefinerFactory.h REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)       # libtinyobjloader-dev: .obj meshes for hdhair-convert
if(HDHAIR_BUILD_TESTS)
  find_package(GTest REQUIRED)                    # libgtest-dev
endif()
if(HDHAIR_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)                # libbenchmark-dev
endif()

add_library(hdhair_osmesa INTERFACE)
target_include_directories(hdhair_osmesa SYSTEM INTERFACE ${OSMESA_INCLUDE_DIR})
target_link_libraries(hdhair_osmesa INTERFACE ${OSMESA_LIBRARY})

add_library(hdhair_opensubdiv INTERFACE)
target_include_directories(hdhair_opensubdiv SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(hdhair_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})
