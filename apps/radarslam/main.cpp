// radarslam: radar SLAM from the command line. `radarslam --help` lists the subcommands.
#include <exception>
#include <iostream>
#include <string>

#include <radarslam/core/cleanup_on_signal.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/version.h>
#include <radarslam/obs/registration.h>

#include "command.h"

namespace radarslam::cli {
std::map<std::string, Command>& commandRegistry() {
  static std::map<std::string, Command> registry;
  return registry;
}
}  // namespace radarslam::cli

namespace {
void printUsage(std::ostream& os) {
  os << "radarslam " << radarslam::versionText() << " - radar SLAM for 360° spinning FMCW radars\n\n"
     << "Usage: radarslam <command> [options]    (radarslam <command> --help for details)\n\nCommands:\n";
  for (const auto& [name, cmd] : radarslam::cli::commandRegistry())
    os << "  " << name << std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') << cmd.summary << "\n";
}
}  // namespace

int main(int argc, char** argv) {
  radarslam::installCleanupOnSignal();  // Ctrl-C removes temporary outputs
  radarslam::registerRadarslamClasses();
  if (argc < 2) {
    printUsage(std::cerr);
    return 2;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    printUsage(std::cout);
    return 0;
  }
  if (name == "--version") {
    std::cout << "radarslam " << radarslam::versionText() << "\n";
    return 0;
  }
  const auto& registry = radarslam::cli::commandRegistry();
  const auto it = registry.find(name);
  if (it == registry.end()) {
    std::cerr << "radarslam: error: unknown command '" << name << "' (see radarslam --help)\n";
    return 2;
  }
  std::string argv0 = "radarslam " + name;
  argv[1] = argv0.data();
  try {
    return it->second.run(argc - 1, argv + 1);
  } catch (const radarslam::InputError& e) {
    std::cerr << "radarslam: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radarslam: error: " << radarslam::describeException(e) << "\n";
    return 1;
  }
}
