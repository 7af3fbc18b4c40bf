# radarslam_module(NAME [DEPS ...] [PRIVATE_DEPS ...])
# One static library per folder libradarslam/src/NAME, headers in
# libradarslam/include/radarslam/NAME. Sources are globbed so a new .cpp needs no CMake edit.
function(radarslam_module name)
  cmake_parse_arguments(M "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB _srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/libradarslam/src/${name}/*.cpp)
  # Installed and exported as radarslam::NAME (cmake/Install.cmake).
  set_property(GLOBAL APPEND PROPERTY RADARSLAM_MODULE_TARGETS radarslam_${name})
  if(NOT _srcs)  # a header-only (or not yet written) module
    add_library(radarslam_${name} INTERFACE)
    target_include_directories(radarslam_${name} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/libradarslam/include>
                                                           $<INSTALL_INTERFACE:include>)
    target_link_libraries(radarslam_${name} INTERFACE ${M_DEPS})
    add_library(radarslam::${name} ALIAS radarslam_${name})
    set_target_properties(radarslam_${name} PROPERTIES EXPORT_NAME ${name})
    return()
  endif()
  add_library(radarslam_${name} STATIC ${_srcs})
  add_library(radarslam::${name} ALIAS radarslam_${name})
  target_include_directories(radarslam_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/libradarslam/include>
                                                      $<INSTALL_INTERFACE:include>)
  target_link_libraries(radarslam_${name} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS}
                                                 $<BUILD_INTERFACE:radarslam_warnings>)
  set_target_properties(radarslam_${name} PROPERTIES EXPORT_NAME ${name})
endfunction()

# radarslam_test(NAME DEPS ...): one GoogleTest executable from test/NAME/*.cpp.
function(radarslam_test name)
  cmake_parse_arguments(T "" "" "DEPS" ${ARGN})
  file(GLOB _srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/${name}/*.cpp)
  if(NOT _srcs)
    return()
  endif()
  add_executable(test_${name} ${_srcs})
  target_link_libraries(test_${name} PRIVATE ${T_DEPS} radarslam_test_support GTest::gtest_main
                                             radarslam_warnings)
  gtest_discover_tests(test_${name} DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 600)
endfunction()
