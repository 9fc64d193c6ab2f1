# Installation of the CMake package CBC3D, so that an outside project can do
#
#   find_package(CBC3D REQUIRED)          # after find_package(ParaView), or on its own
#   target_link_libraries(app PRIVATE CBC3D::Filters)
#
# Included at the end of the top-level CMakeLists.txt, after vtk_module_build and
# paraview_plugin_build. What those already install (see vtkModule.cmake, VTK 9.2):
#   lib/libvtkCBC3DFilters.so, include/cbc3d/*.h (public headers only: vtkCBC3DConvert.h is a
#   PRIVATE_CLASS and the VTK-free core's headers are never installed),
#   lib/cmake/cbc3d/CBC3D-targets*.cmake (export set CBC3D: the target CBC3D::Filters) and
#   CBC3D-vtk-module-properties.cmake (the module's VTK properties), the wrapping hierarchy
#   file, the plugin lib/paraview-5.11/plugins/CBC3D/CBC3D.so (and the client-server wrapping
#   archive libvtkCBC3DFiltersCS.a, which only the plugin needed at link time); the cbc3d
#   command installs itself (Applications/cbc3d).
# What is missing and added here: CBC3DConfig.cmake (finds VTK, includes the targets and the
# module properties), CBC3DConfigVersion.cmake, and CBC3D-vtk-module-find-packages.cmake (the
# module's vtk_module_find_package calls, none today; written so they are exported if added).
#
# cbc3d_core is a static library linked PRIVATE into the shared module: it appears neither in
# the export set nor in CBC3D::Filters' interface, and consumers need no Eigen or OpenMP
# (libvtkCBC3DFilters.so carries libgomp as its own NEEDED entry).

include(CMakePackageConfigHelpers)

set(CBC3D_INSTALL_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/cbc3d")   # as in vtk_module_build
set(CBC3D_BUILD_CMAKE_DIR "${CMAKE_BINARY_DIR}/${CBC3D_INSTALL_CMAKE_DIR}")
set(CBC3D_PLUGIN_SUBDIR "${CMAKE_INSTALL_LIBDIR}/paraview-5.11/plugins/CBC3D")

# The VTK modules CBC3D::Filters' exported interface names (public and private dependencies:
# the private ones appear as IMPORTED_LINK_DEPENDENT_LIBRARIES), for find_package(VTK).
set(CBC3D_VTK_COMPONENTS)
foreach(_cbc3d_module IN LISTS cbc3d_modules)
  get_property(_cbc3d_depends GLOBAL PROPERTY "_vtk_module_${_cbc3d_module}_depends")
  get_property(_cbc3d_private GLOBAL PROPERTY "_vtk_module_${_cbc3d_module}_private_depends")
  foreach(_cbc3d_depend IN LISTS _cbc3d_depends _cbc3d_private)
    if(_cbc3d_depend MATCHES "^VTK::(.+)$")
      list(APPEND CBC3D_VTK_COMPONENTS "${CMAKE_MATCH_1}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES CBC3D_VTK_COMPONENTS)
set(CBC3D_VTK_VERSION "${VTK_MAJOR_VERSION}.${VTK_MINOR_VERSION}")
set(CBC3D_PARAVIEW_VERSION "${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}")

vtk_module_export_find_packages(
  CMAKE_DESTINATION "${CBC3D_INSTALL_CMAKE_DIR}"
  FILE_NAME "CBC3D-vtk-module-find-packages.cmake"
  MODULES ${cbc3d_modules})

# The same config file serves the build tree (build/lib/cmake/cbc3d, next to the build-tree
# export written by vtk_module_build) and the install tree.
configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/CBC3DConfig.cmake.in"
  "${CBC3D_BUILD_CMAKE_DIR}/CBC3DConfig.cmake"
  INSTALL_DESTINATION "${CBC3D_BUILD_CMAKE_DIR}"
  INSTALL_PREFIX "${CMAKE_BINARY_DIR}"
  PATH_VARS CMAKE_INSTALL_BINDIR CMAKE_INSTALL_INCLUDEDIR CBC3D_PLUGIN_SUBDIR)
configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/CBC3DConfig.cmake.in"
  "${CMAKE_BINARY_DIR}/CMakeFiles/CBC3DConfig.cmake.install"
  INSTALL_DESTINATION "${CBC3D_INSTALL_CMAKE_DIR}"
  PATH_VARS CMAKE_INSTALL_BINDIR CMAKE_INSTALL_INCLUDEDIR CBC3D_PLUGIN_SUBDIR)
write_basic_package_version_file(
  "${CBC3D_BUILD_CMAKE_DIR}/CBC3DConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)

install(
  FILES "${CMAKE_BINARY_DIR}/CMakeFiles/CBC3DConfig.cmake.install"
  DESTINATION "${CBC3D_INSTALL_CMAKE_DIR}"
  RENAME "CBC3DConfig.cmake"
  COMPONENT development)
install(
  FILES "${CBC3D_BUILD_CMAKE_DIR}/CBC3DConfigVersion.cmake"
  DESTINATION "${CBC3D_INSTALL_CMAKE_DIR}"
  COMPONENT development)
