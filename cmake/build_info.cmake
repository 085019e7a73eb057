# The build's identity for `rsl --version`: a generated source that defines
# rsl::build_commit() and rsl::build_type(). The commit is read on every build
# (a custom target runs cmake/write_build_info.cmake), and the file is only
# rewritten when it changes, so an unchanged tree recompiles nothing.
set(RSL_BUILD_INFO_SOURCE ${PROJECT_BINARY_DIR}/generated/build_info_values.cpp)
set(rsl_build_type "${CMAKE_BUILD_TYPE}")
if(CMAKE_CONFIGURATION_TYPES)
  set(rsl_build_type "$<CONFIG>")
endif()
add_custom_target(rsl_build_info
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUTPUT=${RSL_BUILD_INFO_SOURCE}
          -DBUILD_TYPE=${rsl_build_type} -P ${PROJECT_SOURCE_DIR}/cmake/write_build_info.cmake
  BYPRODUCTS ${RSL_BUILD_INFO_SOURCE}
  COMMENT "Reading the git commit for rsl --version"
  VERBATIM)

# <rsl/version.h>: the version as macros, for code built against an installed rsl.
configure_file(${PROJECT_SOURCE_DIR}/cmake/version.h.in ${PROJECT_BINARY_DIR}/generated/include/rsl/version.h @ONLY)
