# Makes the installed tree a CMake package (find_package(ProxyGI)) and the
# build a pair of Debian packages (cpack -G DEB: proxygi, proxygi-dev).
# Included from the top-level CMakeLists.txt after vtk_module_build.
include(CMakePackageConfigHelpers)

set(proxygi_cmake_destination "${CMAKE_INSTALL_LIBDIR}/cmake/proxygi")

# The VTK modules the ProxyGI targets name, public and private (a static
# build names the private ones too), found again by the config.
set(proxygi_config_vtk_components)
foreach (proxygi_module IN LISTS proxygi_modules)
  foreach (proxygi_kind IN ITEMS depends private_depends)
    get_property(proxygi_deps GLOBAL PROPERTY "_vtk_module_${proxygi_module}_${proxygi_kind}")
    foreach (proxygi_dep IN LISTS proxygi_deps)
      if (proxygi_dep MATCHES "^VTK::(.+)$")
        list(APPEND proxygi_config_vtk_components "${CMAKE_MATCH_1}")
      endif ()
    endforeach ()
  endforeach ()
endforeach ()
list(REMOVE_DUPLICATES proxygi_config_vtk_components)
list(SORT proxygi_config_vtk_components)
string(REPLACE ";" " " proxygi_config_vtk_components "${proxygi_config_vtk_components}")

# Embree, OpenEXR and Highway are private to shared libraries, so a consumer needs
# them only when the libraries are static.
set(proxygi_config_third_party "")
if (NOT BUILD_SHARED_LIBS)
  set(proxygi_config_third_party
    "find_dependency(embree 3)\nfind_dependency(OpenEXR 3)\nfind_dependency(hwy 1.0)\n")
endif ()

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/ProxyGIConfig.cmake.in"
  "${CMAKE_BINARY_DIR}/${proxygi_cmake_destination}/ProxyGIConfig.cmake"
  INSTALL_DESTINATION "${proxygi_cmake_destination}"
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR)
write_basic_package_version_file(
  "${CMAKE_BINARY_DIR}/${proxygi_cmake_destination}/ProxyGIConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)
install(
  FILES
    "${CMAKE_BINARY_DIR}/${proxygi_cmake_destination}/ProxyGIConfig.cmake"
    "${CMAKE_BINARY_DIR}/${proxygi_cmake_destination}/ProxyGIConfigVersion.cmake"
  DESTINATION "${proxygi_cmake_destination}"
  COMPONENT   development)

# Debian packages: the libraries and proxygi (runtime), headers and CMake
# files (development). Shared-library dependencies come from dpkg-shlibdeps;
# the development package adds what the config finds.
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "proxygi")
set(CPACK_PACKAGE_VENDOR "ProxyGI")
set(CPACK_PACKAGE_CONTACT "ProxyGI developers <proxygi@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Soft shadows and indirect light for VTK from sphere proxies and spherical harmonics")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime development)
set(CPACK_DEBIAN_FILE_NAME "DEB-DEFAULT")
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME "proxygi")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME "proxygi-dev")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION "libdevel")
# The config finds VTK, which Debian ships with ParaView's SDK (whose CMake
# files need python3-paraview) or as libvtk9-dev.
set(proxygi_deb_vtk_dev "paraview-dev, python3-paraview")
if (NOT VTK_DIR MATCHES "paraview")
  set(proxygi_deb_vtk_dev "libvtk9-dev")
endif ()
# proxygi (= version) comes from the component dependency.
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS "${proxygi_deb_vtk_dev}")
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)
set(CPACK_COMPONENT_DEVELOPMENT_DEPENDS runtime)
include(CPack)
