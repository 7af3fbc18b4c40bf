#include "radarslam/obs/registration.h"

#include <mrpt/rtti/CObject.h>

#include <mutex>

#include "radarslam/obs/CObservationRadarScan.h"

namespace radarslam {

void registerRadarslamClasses() {
  static std::once_flag once;
  std::call_once(once, [] { mrpt::rtti::registerClass(CLASS_ID(CObservationRadarScan)); });
}

}  // namespace radarslam
