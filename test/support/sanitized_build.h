#pragma once
// RADARSLAM_SANITIZED_BUILD is defined (1) when this translation unit is compiled with
// AddressSanitizer (GCC: __SANITIZE_ADDRESS__; clang: __has_feature(address_sanitizer)), e.g. the
// RADARSLAM_SANITIZE=address,undefined build of cmake/Sanitizers.cmake. Tests that cannot run
// instrumented (or have a known failure there) skip on it.
#if defined(__SANITIZE_ADDRESS__)
#define RADARSLAM_SANITIZED_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RADARSLAM_SANITIZED_BUILD 1
#endif
#endif
