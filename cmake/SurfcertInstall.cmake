# `cmake --install`: the static libraries of the five layers, their public headers (the API
# header <surfcert/surfcert.hpp> includes the engine's typed results), the `surfcert`
# executable (and surfcert-mpi, in a build with MPI), and a CMake package (lib/cmake/surfcert)
# exporting surfcert::surfcert.
include(CMakePackageConfigHelpers)
install(TARGETS surfcert_core surfcert_algebra surfcert_certify surfcert_trace surfcert_app
                surfcert_api
  EXPORT surfcertTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(layer core algebra certify trace)
  set_target_properties(surfcert_${layer} PROPERTIES EXPORT_NAME ${layer})
endforeach()
set_target_properties(surfcert_app PROPERTIES EXPORT_NAME app)
install(TARGETS surfcert RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# `surfcert batch --mpi` execs the surfcert-mpi next to it (app/CMakeLists.txt): same directory.
if(TARGET surfcert-mpi)
  install(TARGETS surfcert-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
foreach(layer core algebra certify trace app)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
set(_cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/surfcert)
install(EXPORT surfcertTargets NAMESPACE surfcert:: DESTINATION ${_cfgdir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/surfcertConfig.cmake.in
  ${PROJECT_BINARY_DIR}/surfcertConfig.cmake INSTALL_DESTINATION ${_cfgdir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/surfcertConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/surfcertConfig.cmake
              ${PROJECT_BINARY_DIR}/surfcertConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindFLINT.cmake
  DESTINATION ${_cfgdir})
