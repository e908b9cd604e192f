# One GL loader for both EGL and OSMesa: glad2 (python3-glad) generates an
# OpenGL 4.5 core loader at build time. Its gladLoadGL() takes any
# get-proc-address function, so eglGetProcAddress and OSMesaGetProcAddress
# both feed it. --reproducible keeps glad from fetching specs over the network.
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(HDHAIR_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${HDHAIR_GLAD_DIR}/src/gl.c ${HDHAIR_GLAD_DIR}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --api gl:core=4.5 --extensions GL_KHR_debug
          --out-path ${HDHAIR_GLAD_DIR} --reproducible --quiet c
  COMMENT "Generating the OpenGL 4.5 core loader with glad"
  VERBATIM)
add_library(hdhair_glad STATIC ${HDHAIR_GLAD_DIR}/src/gl.c)
target_include_directories(hdhair_glad SYSTEM PUBLIC ${HDHAIR_GLAD_DIR}/include)
set_target_properties(hdhair_glad PROPERTIES C_VISIBILITY_PRESET hidden)
