// `radarslam convert PATH OUT.rawlog`: any supported dataset to an MRPT rawlog of
// CObservationRadarScan (gzip level 1, written atomically), with progress and a summary.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/output_path.h>
#include <radarslam/io/dataset.h>
#include <radarslam/io/rawlog_writer.h>

#include "cli_common.h"
#include "command.h"
#include "progress_line.h"

namespace radarslam::cli {
namespace {

using Clock = std::chrono::steady_clock;

int runConvert(int argc, char** argv) {
  CommandLine cmd(
      "convert",
      "Converts a radar dataset (Oxford, MulRan, Boreas, RADIATE, or a .rawlog) to an MRPT .rawlog of "
      "radarslam CObservationRadarScan observations (gzip level 1, written atomically).");
  TCLAP::UnlabeledValueArg<std::string> path_arg("path", "Dataset directory or .rawlog file", true, "",
                                                 "PATH", cmd.tclap());
  TCLAP::UnlabeledValueArg<std::string> out_arg(
      "out", "Output .rawlog file (a regular file there is replaced)", true, "", "OUT", cmd.tclap());
  TCLAP::SwitchArg skip_arg("", "skip-bad-scans", "Warn about and skip scans that fail to decode or check",
                            cmd.tclap());
  TCLAP::ValueArg<long long> first_arg("", "first", "First scan index to convert (0-based)", false, 0, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<long long> count_arg("", "count", "Number of scans to convert (default: all)", false, -1,
                                       "N", cmd.tclap());
  TCLAP::ValueArg<double> res_arg("", "range-resolution", "Override the range resolution [m/bin]", false, 0.0,
                                  "M", cmd.tclap());
  TCLAP::ValueArg<double> offset_arg("", "range-offset", "Override the range of bin 0 [m]", false, 0.0, "M",
                                     cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam convert";
  if (first_arg.getValue() < 0) throw InputError(where, "--first must be >= 0");
  if (count_arg.isSet() && count_arg.getValue() < 0) throw InputError(where, "--count must be >= 0");
  if (res_arg.isSet() && !(res_arg.getValue() > 0.0))
    throw InputError(where, "--range-resolution must be > 0");
  const std::filesystem::path path = path_arg.getValue(), out = out_arg.getValue();
  checkNoOverlap(path, out);
  checkFileOutput(out, "OUT");
  if (out.extension() != ".rawlog") throw InputError(out.string(), "output must be a .rawlog file");

  ReaderOptions options;
  options.range_resolution_m = res_arg.getValue();
  if (offset_arg.isSet()) options.range_offset_m = offset_arg.getValue();
  const auto reader = openDataset(path, options);
  const auto first = static_cast<std::size_t>(first_arg.getValue());
  const std::size_t end =
      count_arg.getValue() < 0 ? reader->size() : first + static_cast<std::size_t>(count_arg.getValue());
  ScanIterator it(*reader, skip_arg.getValue(), first, end);

  std::size_t written = 0;
  ProgressLine progress("convert", it.total());
  writeFileAtomically(out, [&](const std::filesystem::path& tmp) {
    RawlogWriter writer(tmp, 1);
    std::size_t visited = 0;
    while (auto scan = it.next()) {
      writer.write(*scan);
      visited = it.index() + 1 - first;
      progress.update(visited);
    }
    writer.close();
    written = writer.count();
    if (written == 0)  // thrown here, the previous OUT stays as it was
      throw InputError(path.string(),
                       "no scan could be converted (" + std::to_string(it.skipped()) + " skipped)");
  });
  progress.finish(it.total());
  std::cout << "converted " << written << " scans of " << toString(reader->kind()) << " " << path.string()
            << " to " << out.string() << " in " << progress.elapsedSeconds() << " s; skipped " << it.skipped()
            << " bad scan(s)\n";
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("convert", "Convert a radar dataset to an MRPT .rawlog of radar scans", runConvert);

}  // namespace radarslam::cli
