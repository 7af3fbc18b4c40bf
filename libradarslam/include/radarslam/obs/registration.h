#pragma once

namespace radarslam {

/// Registers radarslam's serializable classes with MRPT's class registry. Must be called before
/// reading a rawlog: MRPT's automatic registration is dropped when linking static libraries, and
/// CRawlog then "loads" files with zero entries. Idempotent and thread-safe.
void registerRadarslamClasses();

}  // namespace radarslam
