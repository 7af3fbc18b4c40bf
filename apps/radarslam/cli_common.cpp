#include "cli_common.h"

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/core/version.h>

namespace radarslam::cli {

namespace {
// TCLAP prints usage on error and calls exit; we want one line and our own exit code.
class OneLineOutput : public TCLAP::StdOutput {
 public:
  void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override { throw e; }
};
}  // namespace

CommandLine::CommandLine(const std::string& name, const std::string& description)
    : name_("radarslam " + name),
      cmd_(description, ' ', radarslam::versionText()),
      verbosity_("", "verbosity", "Log level: DEBUG, INFO, WARN or ERROR", false, "INFO", "LEVEL", cmd_) {}

void CommandLine::parse(int argc, char** argv) {
  static OneLineOutput output;
  cmd_.setOutput(&output);
  try {
    cmd_.parse(argc, argv);
  } catch (TCLAP::ArgException& e) {
    throw InputError(
        name_,
        e.error() + (e.argId().empty() || e.argId() == " " ? "" : " (" + e.argId() + ")") + "; see --help");
  }
  logger().setMinLoggingLevel(parseVerbosity(verbosity_.getValue()));
}

}  // namespace radarslam::cli
