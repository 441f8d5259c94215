# The installed CMake package: GrowingLeastSquaresConfig.cmake and its version file beside the module's targets
# file (vtk_module_build's export set GrowingLeastSquares) in GLS_CMAKE_DESTINATION. Included by the top-level
# CMakeLists.txt after the module, the wrapping and the plugin are defined.
include(CMakePackageConfigHelpers)

# The VTK components the config must find: the module's own dependencies, as vtk.module lists them.
get_target_property(gls_vtk_depends GLS::Filters INTERFACE_vtk_module_depends)
get_target_property(gls_vtk_private_depends GLS::Filters INTERFACE_vtk_module_private_depends)
set(GLS_CONFIG_VTK_COMPONENTS "")
foreach(module IN LISTS gls_vtk_depends gls_vtk_private_depends)
  string(REGEX REPLACE "^VTK::" "" component "${module}")
  list(APPEND GLS_CONFIG_VTK_COMPONENTS "${component}")
endforeach()
get_filename_component(GLS_CONFIG_VTK_DIR "${VTK_DIR}" REALPATH)
# What the build holds, as TRUE/FALSE for the config's if()s.
foreach(flag STATIC_MODULE CUDA PLUGIN)
  set(GLS_CONFIG_${flag} FALSE)
endforeach()
if(NOT BUILD_SHARED_LIBS)
  set(GLS_CONFIG_STATIC_MODULE TRUE)
endif()
if(GLS_ENABLE_CUDA)
  set(GLS_CONFIG_CUDA TRUE)
endif()
if(GLS_BUILD_PLUGIN)
  set(GLS_CONFIG_PLUGIN TRUE)
endif()
set(GLS_PLUGIN_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/${GLS_PLUGIN_SUBDIRECTORY}")
if(NOT DEFINED GLS_PYTHON_DESTINATION)
  set(GLS_PYTHON_DESTINATION "${CMAKE_INSTALL_LIBDIR}/python3/dist-packages")
endif()

configure_package_config_file(cmake/GrowingLeastSquaresConfig.cmake.in
  "${CMAKE_CURRENT_BINARY_DIR}/GrowingLeastSquaresConfig.cmake"
  INSTALL_DESTINATION "${GLS_CMAKE_DESTINATION}"
  PATH_VARS GLS_PLUGIN_INSTALL_DIR GLS_PYTHON_DESTINATION)
# 0.x: a minor version may change the interface.
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/GrowingLeastSquaresConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}" COMPATIBILITY SameMinorVersion)
install(FILES
  "${CMAKE_CURRENT_BINARY_DIR}/GrowingLeastSquaresConfig.cmake"
  "${CMAKE_CURRENT_BINARY_DIR}/GrowingLeastSquaresConfigVersion.cmake"
  DESTINATION "${GLS_CMAKE_DESTINATION}")
