# Installs the framework as a CMake package: find_package(geotandem) gives geotandem::<part>.
include(CMakePackageConfigHelpers)

# The plugin interface alone (geotandem/workflow/plugin_abi.h, a C header). A plugin compiles
# against it and links no framework library: the host that loads it has them loaded already.
add_library(geotandem_plugin_abi INTERFACE)
add_library(geotandem::plugin_abi ALIAS geotandem_plugin_abi)
set_target_properties(geotandem_plugin_abi PROPERTIES EXPORT_NAME plugin_abi)
target_include_directories(geotandem_plugin_abi INTERFACE
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/framework/workflow/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

get_property(_geotandem_targets GLOBAL PROPERTY GEOTANDEM_EXPORTED_TARGETS)
install(TARGETS ${_geotandem_targets} geotandem_plugin_abi EXPORT geotandemTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT geotandemTargets NAMESPACE geotandem:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geotandem)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/geotandemConfig.cmake.in
  ${PROJECT_BINARY_DIR}/geotandemConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geotandem)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/geotandemConfigVersion.cmake COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/geotandemConfig.cmake ${PROJECT_BINARY_DIR}/geotandemConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/geotandem)
