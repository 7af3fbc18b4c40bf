# Sanitizer and fuzzer build options (docs/hardening.md).
#
# RADARSLAM_SANITIZE=address,undefined  builds our libraries, programs and tests with
#   -fsanitize=<list> -fno-omit-frame-pointer -fno-sanitize-recover=all (any report is fatal).
#   LeakSanitizer comes with ASan on Linux. Third-party libraries (MRPT, OpenCV) are the
#   uninstrumented Debian builds; ASan still checks their heap use through its allocator.
# RADARSLAM_BUILD_FUZZERS=ON  builds the libFuzzer targets in test/fuzz (clang only): our code is
#   compiled with -fsanitize=fuzzer-no-link,address,undefined, the fuzz programs link -fsanitize=fuzzer.
set(RADARSLAM_SANITIZE "" CACHE STRING "Comma-separated -fsanitize= list for all our targets, e.g. address,undefined")
option(RADARSLAM_BUILD_FUZZERS "Build libFuzzer targets (test/fuzz, clang only)" OFF)

if(RADARSLAM_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "RADARSLAM_BUILD_FUZZERS needs clang (e.g. -DCMAKE_CXX_COMPILER=clang++-14)")
  endif()
  if(NOT RADARSLAM_SANITIZE)
    set(RADARSLAM_SANITIZE "address,undefined")
  endif()
  # Instrument all our code for coverage feedback; only the fuzz programs get libFuzzer's main().
  add_compile_options(-fsanitize=fuzzer-no-link)
  # Our warning set is GCC's (-Wshadow=local); clang only checks the code here, GCC CI owns -Werror.
  add_compile_options(-Wno-unknown-warning-option)
endif()

if(RADARSLAM_SANITIZE)
  message(STATUS "radarslam: sanitizers ${RADARSLAM_SANITIZE}")
  add_compile_options(-fsanitize=${RADARSLAM_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${RADARSLAM_SANITIZE})
endif()
