# Every dependency comes from a Debian 12 package; README.md lists which and why.
find_package(Threads REQUIRED)
find_package(glm REQUIRED)                        # libglm-dev
find_package(TBB REQUIRED)                        # libtbb-dev
find_package(fmt REQUIRED)                        # libfmt-dev
find_package(CLI11 REQUIRED)                      # libcli11-dev
find_package(nlohmann_json REQUIRED)              # nlohmann-json3-dev
find_package(OpenImageIO REQUIRED)                # libopenimageio-dev
find_package(OpenEXR REQUIRED)                    # libopenexr-dev
find_package(OpenGL REQUIRED COMPONENTS EGL)      # libegl-dev
find_library(OSMESA_LIBRARY NAMES OSMesa REQUIRED) # libosmesa6-dev
find_path(OSMESA_INCLUDE_DIR GL/osmesa.h REQUIRED)
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED) # glslang-tools
if(HDHAIR_BUILD_TESTS)
  find_package(GTest REQUIRED)                    # libgtest-dev
endif()
if(HDHAIR_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)                # libbenchmark-dev
endif()

add_library(hdhair_osmesa INTERFACE)
target_include_directories(hdhair_osmesa SYSTEM INTERFACE ${OSMESA_INCLUDE_DIR})
target_link_libraries(hdhair_osmesa INTERFACE ${OSMESA_LIBRARY})
