#pragma once
// Subcommands of the `radarslam` program register themselves with RADARSLAM_COMMAND in their own
// cmd_*.cpp file; main() dispatches on the first argument. A command returns the process exit
// code; InputError and other exceptions are turned into a one-line error by main().
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace radarslam::cli {

struct Command {
  std::string summary;
  std::function<int(int argc, char** argv)> run;  // argv[0] is "radarslam <name>"
};

std::map<std::string, Command>& commandRegistry();

struct CommandRegistrar {
  CommandRegistrar(const std::string& name, std::string summary, std::function<int(int, char**)> run) {
    commandRegistry()[name] = Command{std::move(summary), std::move(run)};
  }
};

}  // namespace radarslam::cli

#define RADARSLAM_COMMAND(name, summary, fn) \
  static const ::radarslam::cli::CommandRegistrar radarslam_command_registrar_##fn(name, summary, fn)
