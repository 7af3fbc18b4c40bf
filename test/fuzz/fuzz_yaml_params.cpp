// Fuzz target: YAML configs. YamlParams::fromText (MRPT's YAML parser) then the radar module's
// loadParams for the `cartesian:` and `peak_cloud:` sections, every get() type, unknown keys.
#include "fuzz_common.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/radar/cartesian.h"
#include "radarslam/radar/peak_cloud.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  radarslam::fuzz::expectOnlyInputError([&] {
    const auto yaml = radarslam::YamlParams::fromText(text, "fuzz.yaml");
    radarslam::CartesianParams cartesian;
    radarslam::loadParams(yaml.section("cartesian"), cartesian);
    radarslam::PeakCloudParams peaks;
    radarslam::loadParams(yaml.section("peak_cloud"), peaks);
    const auto other = yaml.section("other");
    double d = 0;
    float f = 0;
    int i = 0;
    unsigned u = 0;
    bool b = false;
    std::string s;
    std::vector<double> v;
    other.get("d", d);
    other.get("f", f);
    other.get("i", i);
    other.get("u", u);
    other.get("b", b);
    other.get("s", s);
    other.get("v", v);
    yaml.rejectUnknownKeys();
  });
  return 0;
}
