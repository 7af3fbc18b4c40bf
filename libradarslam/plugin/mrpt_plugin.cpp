// libradarslam_mrpt_plugin.so: lets MRPT's own tools read radarslam rawlogs.
//
//   rawlog-edit --plugins libradarslam_mrpt_plugin.so -i scans.rawlog --info
//   RawLogViewer (File > Load plugins), or any program that calls mrpt::system::loadPluginModules
//
// Loading the library registers radarslam::CObservationRadarScan with MRPT's class registry, so
// CArchive can deserialise it (otherwise: "Stored object has class 'radarslam::CObservationRadarScan'
// which is not registered!"). MRPT runs no entry point of a plugin: registration happens in the
// library's static initialiser, on dlopen().
#include "radarslam/obs/registration.h"

namespace {
const bool registered = [] {
  radarslam::registerRadarslamClasses();
  return true;
}();
}  // namespace
