# Install rules, the CMake package (find_package(radarslam CONFIG)), pkg-config file, Debian
# package (CPack) and the map server's systemd unit. Layout: GNUInstallDirs.
#   cmake --install build --prefix /opt/radarslam        (README, "Install")
#   cd build && cpack -G DEB                              -> radarslam_<version>_amd64.deb
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(RADARSLAM_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/radarslam)
set(RADARSLAM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/radarslam)

# Programs, the MRPT plugin, libraries (exported) and public headers.
install(TARGETS radarslam radarslam-map-server radarslam-map-client radarslam-scan-publisher
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS radarslam_mrpt_plugin LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS ${RADARSLAM_MODULE_TARGETS} radarslam_dds_types EXPORT radarslamTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libradarslam/include/radarslam DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# Resources: IDL, default configs (the programs look in <bindir>/../share/radarslam/config).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/share/idl DESTINATION ${RADARSLAM_INSTALL_DATADIR})
file(GLOB _radarslam_configs ${PROJECT_SOURCE_DIR}/config/*.yaml ${PROJECT_SOURCE_DIR}/config/*.xml)
install(FILES ${_radarslam_configs} DESTINATION ${RADARSLAM_INSTALL_DATADIR}/config)

# CMake package.
install(EXPORT radarslamTargets NAMESPACE radarslam:: DESTINATION ${RADARSLAM_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/radarslamConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/radarslamConfig.cmake INSTALL_DESTINATION ${RADARSLAM_INSTALL_CMAKEDIR}
                              PATH_VARS RADARSLAM_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/radarslamConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/radarslamConfig.cmake ${PROJECT_BINARY_DIR}/radarslamConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindLibdeflate.cmake DESTINATION ${RADARSLAM_INSTALL_CMAKEDIR})

# pkg-config: our static libraries in link order, then MRPT's (Debian ships no .pc for MRPT).
set(RADARSLAM_PC_LIBS "")
foreach(_m reloc slam dds map loop backend frontend sim eval radar io obs core)
  if(TARGET radarslam_${_m})
    get_target_property(_type radarslam_${_m} TYPE)
    if(NOT _type STREQUAL "INTERFACE_LIBRARY")
      string(APPEND RADARSLAM_PC_LIBS " -lradarslam_${_m}")
    endif()
  endif()
endforeach()
string(APPEND RADARSLAM_PC_LIBS " -lradarslam_dds_types")
set(RADARSLAM_PC_MRPT_CFLAGS "")
set(RADARSLAM_PC_MRPT_LIBS "")
foreach(_m slam graphslam maps tfest obs graphs opengl poses bayes img math serialization config system io containers
           random expr rtti typemeta core)
  if(TARGET mrpt::${_m})
    get_target_property(_inc mrpt::${_m} INTERFACE_INCLUDE_DIRECTORIES)
    foreach(_d ${_inc})
      if(NOT _d MATCHES "\\$<" AND NOT RADARSLAM_PC_MRPT_CFLAGS MATCHES "-I${_d} ")
        string(APPEND RADARSLAM_PC_MRPT_CFLAGS "-I${_d} ")
      endif()
    endforeach()
    get_target_property(_type mrpt::${_m} TYPE)
    if(NOT _type STREQUAL "INTERFACE_LIBRARY")
      string(APPEND RADARSLAM_PC_MRPT_LIBS " -lmrpt-${_m}")
    endif()
  endif()
endforeach()
string(APPEND RADARSLAM_PC_LIBS "${RADARSLAM_PC_MRPT_LIBS} -lceres -lglog -lpthread")
set(RADARSLAM_PC_MRPT_LIBS "")
configure_file(${PROJECT_SOURCE_DIR}/cmake/radarslam.pc.in ${PROJECT_BINARY_DIR}/radarslam.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/radarslam.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The map server as a system service (docs/dds.md): one instance per map name. The unit needs the
# absolute install prefix, known only at install time (cpack installs into /usr).
configure_file(${PROJECT_SOURCE_DIR}/cmake/InstallService.cmake.in ${PROJECT_BINARY_DIR}/InstallService.cmake @ONLY)
install(SCRIPT ${PROJECT_BINARY_DIR}/InstallService.cmake)
install(FILES ${PROJECT_SOURCE_DIR}/share/systemd/radarslam.sysusers DESTINATION lib/sysusers.d RENAME radarslam.conf)

# Debian package: cpack -G DEB. Runtime dependencies: the Debian packages of what we link.
set(CPACK_PACKAGE_NAME radarslam)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "radarslam developers <radarslam@users.noreply.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Radar SLAM for 360-degree spinning FMCW radars, with a DDS map server")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # radarslam_<version>_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # Depends: computed by dpkg-shlibdeps from what we link
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "mrpt-apps, octomap-tools, pcl-tools")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_SOURCE_DIR}/share/systemd/postinst ${PROJECT_SOURCE_DIR}/share/systemd/conffiles)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
include(CPack)
