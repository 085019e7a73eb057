# cmake --install: the `rsl` program (shaders are embedded), the Python
# module (python/CMakeLists.txt), the public headers <rsl/…>, the stage
# libraries and an exported CMake package:
#
#   find_package(rsl CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE rsl::rsl)   # the API, include/rsl/rsl.h
#
# The stage libraries are static, so every stage is exported (rsl::core,
# rsl::render, …, with their Debian dependencies found again by rslConfig.cmake);
# their headers stay in the source tree: the installed interface is <rsl/rsl.h>.
# Components: program, python, development; one Debian package each (CPack
# below). docs/API.md.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RSL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/rsl)
set(RSL_EXPORTED_LIBRARIES rsl_core rsl_formats rsl_brdf rsl_lightfit rsl_rays rsl_image rsl_trace rsl_fields rsl_render
  ${RSL_GL_LIB} rsl_backend rsl_version rsl_api)
foreach(library ${RSL_EXPORTED_LIBRARIES})
  string(REGEX REPLACE "^rsl_" "" short ${library})
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${short})
endforeach()
set_target_properties(rsl_api PROPERTIES EXPORT_NAME rsl)

install(TARGETS rsl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT program)
# What `rsl demo` and `rsl bench` read beside an installed rsl (share/rsl,
# tools/rsl/data_folder.h): the demos' scene files, the generated assets they
# and the project's scenes use, and those scenes; never a field cache.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/demos/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rsl/demos COMPONENT program
  FILES_MATCHING PATTERN "*.json" PATTERN ".rsl-cache" EXCLUDE)
install(DIRECTORY ${RSL_GENERATED_DIR}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rsl/assets/generated COMPONENT program
  PATTERN ".rsl-cache" EXCLUDE PATTERN ".*rsl-tmp-*" EXCLUDE PATTERN "yard-*" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rsl/assets/scenes
  COMPONENT program PATTERN ".rsl-cache" EXCLUDE PATTERN ".*rsl-tmp-*" EXCLUDE)
install(TARGETS ${RSL_EXPORTED_LIBRARIES} EXPORT rslTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
install(FILES ${PROJECT_SOURCE_DIR}/include/rsl/rsl.h ${PROJECT_SOURCE_DIR}/include/rsl/error.h
  ${PROJECT_BINARY_DIR}/generated/include/rsl/version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rsl COMPONENT development)
install(EXPORT rslTargets NAMESPACE rsl:: DESTINATION ${RSL_INSTALL_CMAKEDIR} COMPONENT development)

set(RSL_CONFIG_HAVE_GL ${RSL_BUILD_GL})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rslConfig.cmake.in ${PROJECT_BINARY_DIR}/rslConfig.cmake
  INSTALL_DESTINATION ${RSL_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rslConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rslConfig.cmake ${PROJECT_BINARY_DIR}/rslConfigVersion.cmake
  DESTINATION ${RSL_INSTALL_CMAKEDIR} COMPONENT development)

# Debian packages: `cpack -G DEB` in the build folder writes
#   rsl_VERSION_amd64.deb          the program
#   python3-rsl_VERSION_amd64.deb  the module (import rsl)
#   librsl-dev_VERSION_amd64.deb   headers, static libraries, CMake package
# Run-time dependencies come from dpkg-shlibdeps (Debian 12 package names of
# the shared libraries the binaries load); the -dev package depends on the
# -dev packages rslConfig.cmake finds. The default build's binaries run on
# any x86-64-v2 CPU (RSL_MARCH); a build configured with -DRSL_NATIVE=ON (as
# scripts/quickstart.sh's is) uses the build machine's CPU extensions, and its
# packages may stop with an illegal instruction on other machines.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rsl)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "rsl")
set(CPACK_PACKAGE_CONTACT "rsl developers <noreply@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "all-frequency environment lighting of dynamic scenes with rotatable square lights")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL program development)
if(TARGET rsl_python)
  list(APPEND CPACK_COMPONENTS_ALL python)
endif()
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)

set(CPACK_DEBIAN_PROGRAM_PACKAGE_NAME rsl)
# Mesa's drivers (llvmpipe too) for the gl backend and the viewer; the CPU
# renderer needs none. NVIDIA's driver provides its own.
set(CPACK_DEBIAN_PROGRAM_PACKAGE_RECOMMENDS libgl1-mesa-dri)
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-rsl)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME librsl-dev)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
set(rsl_dev_depends libembree-dev libopenexr-dev libeigen3-dev libglm-dev libtbb-dev nlohmann-json3-dev libfmt-dev)
if(RSL_BUILD_GL)
  list(APPEND rsl_dev_depends libgl-dev libegl-dev libopengl-dev)  # the viewer's GLFW and ImGui stay in the program
endif()
list(JOIN rsl_dev_depends ", " CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS)
set(CPACK_DEBIAN_PROGRAM_DESCRIPTION "rsl renderer: the rsl program
 Fits environment maps with rotatable square lights, bakes visibility fields,
 renders dynamic scenes on the CPU or GPU and measures them against an Embree
 ground truth.")
set(CPACK_COMPONENT_PROGRAM_DESCRIPTION "${CPACK_DEBIAN_PROGRAM_DESCRIPTION}")
set(CPACK_COMPONENT_PYTHON_DESCRIPTION "rsl renderer: Python 3 module
 import rsl: fit environments, bake, render frames to numpy arrays, run the
 ground truth and compare.")
set(CPACK_COMPONENT_DEVELOPMENT_DESCRIPTION "rsl renderer: C++ API
 The public header <rsl/rsl.h>, the static libraries and the CMake package
 (find_package(rsl CONFIG REQUIRED), target rsl::rsl).")
include(CPack)
