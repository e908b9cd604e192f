# What `cmake --install` deploys, in two components:
#
#   tools      bin/hdhair-record, bin/hdhair-convert, bin/hdhair-farm (runs the hdhair-record
#              beside it), share/doc/hdhair/{README.md,LICENSE,docs/}
#              (docs/ beside README, so that its links hold),
#              share/hdhair/ocio/config.ocio (hdhair-record's OCIO config, found beside bin/)
#   usdPlugin  plugin/usd/plugInfo.json            (includes */resources/, as OpenUSD's own)
#              plugin/usd/hdHairSchema/resources/  the HdHairAPI schema (no library)
#              plugin/usd/hdHair.so, plugin/usd/hdHairImageReader.so (dome textures,
#              loaded on first use), plugin/usd/hdHair/resources/plugInfo.json  (with OpenUSD)
#
# so that PXR_PLUGINPATH_NAME=<prefix>/plugin/usd is all a host needs. The
# engine's static libraries and headers are not installed: hdHair is used
# through Hydra and its tools, and the engine's C++ interface changes with
# the render graph, so no CMake package config promises one.
#
# CPack makes a Debian package of the tools component alone (hdhair-tools),
# from a build without OpenUSD: the plugin links an OpenUSD that no Debian
# package provides, so it is deployed from a prefix instead (README,
# "Installing").
include(GNUInstallDirs)

install(TARGETS hdhair-record hdhair-convert hdhair-farm RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE
        DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/hdhair COMPONENT tools)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/hdhair/docs COMPONENT tools)
install(FILES ${PROJECT_SOURCE_DIR}/hdHair/image/ocio/config.ocio
        DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/hdhair/ocio COMPONENT tools)
install(FILES ${PROJECT_SOURCE_DIR}/hdHair/reference/cycles/renderCyclesScene.py
        DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/hdhair/cycles COMPONENT tools)

install(FILES ${PROJECT_SOURCE_DIR}/cmake/install/plugInfo.json DESTINATION plugin/usd COMPONENT usdPlugin)
install(FILES ${PROJECT_SOURCE_DIR}/schemas/HdHairAPI/plugInfo.json
              ${PROJECT_SOURCE_DIR}/schemas/HdHairAPI/generatedSchema.usda
              ${PROJECT_SOURCE_DIR}/schemas/HdHairAPI/schema.usda
        DESTINATION plugin/usd/hdHairSchema/resources COMPONENT usdPlugin)

if(HDHAIR_WITH_USD)
  message(STATUS "hdHair: no Debian package from a build with OpenUSD (its hdhair-record links OpenUSD); "
                 "configure with -DHDHAIR_HYDRA=OFF for `cpack -G DEB`")
  return()
endif()
set(CPACK_PACKAGE_NAME hdhair)
set(CPACK_PACKAGE_VENDOR "hdHair")
set(CPACK_PACKAGE_CONTACT "hdHair developers <hdhair@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "hdHair's hair renderer tools: hdhair-record, hdhair-convert and hdhair-farm")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_COMPONENTS_ALL tools)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_TOOLS_PACKAGE_NAME hdhair-tools)
set(CPACK_DEBIAN_TOOLS_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "Renders USD hair (BasisCurves) headless through OpenGL (EGL or OSMesa): hdhair-record, a\nusdrecord-style renderer with an embedded .usda reader, hdhair-convert for TressFX and\nCem Yuksel hair assets, and hdhair-farm, which renders frame ranges across a Slurm cluster. The Hydra plugin is deployed separately, beside its OpenUSD.")
# The libraries the binaries link, as Debian packages (dpkg-shlibdeps), and
# Mesa's drivers, which are loaded at run time and so not seen by it.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_TOOLS_PACKAGE_DEPENDS "libegl-mesa0, libgl1-mesa-dri")
# hdhair-farm runs Slurm's client commands (sbatch, squeue) where a farm has them.
set(CPACK_DEBIAN_TOOLS_PACKAGE_SUGGESTS "slurm-client")
set(CPACK_STRIP_FILES ON)
include(CPack)
