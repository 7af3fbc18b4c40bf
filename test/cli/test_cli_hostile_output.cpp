// The output rule (docs/hardening.md, "Output rule") against a hostile user (issue 15, classes 1,
// 2, 8 and the output side of 10): -o only replaces what radarslam created, inputs and outputs
// never overlap, devices and FIFOs are written in place, symbolic links are written through, every
// check runs before the work, and Ctrl-C leaves no temporary or partial output behind. Each
// refusal must be one line on stderr naming the path, with the existing data byte for byte intact.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.h"
#include "file_contents.h"
#include "radarslam/map/map_io.h"
#include "temp_dir.h"

namespace {

using radarslam::test::readFileBytes;

namespace fs = std::filesystem;
using radarslam::test::CliResult;
using radarslam::test::runCli;
using radarslam::test::shellQuoted;
using Clock = std::chrono::steady_clock;

/// Every entry under `root` (relative path -> type and content): compared before and after a run.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> out;
  if (fs::is_regular_file(root)) return {{"", "file:" + readFileBytes(root)}};
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string rel = fs::relative(e.path(), root).string();
    if (e.is_symlink())
      out[rel] = "link:" + fs::read_symlink(e.path()).string();
    else if (e.is_regular_file())
      out[rel] = "file:" + readFileBytes(e.path());
    else
      out[rel] = "dir";
  }
  return out;
}

/// Hidden entries of `dir` whose name starts with ".NAME" (temporaries, staging, backups of NAME).
std::vector<std::string> leftovers(const fs::path& dir, const std::string& name) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("." + name, 0) == 0) out.push_back(n);
  }
  return out;
}

std::size_t lines(const std::string& s) {
  return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

/// Exit 1 and exactly one stderr line "radarslam: error: ...NEEDLE...".
void expectOneLineError(const CliResult& r, const std::string& needle) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("radarslam: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.err;
}

/// Starts `radarslam args` (stdout and stderr to files in `dir`) without a shell, so that SIGINT
/// keeps its default disposition in the child.
pid_t start(const std::vector<std::string>& args, const fs::path& dir) {
  std::vector<std::string> all = {RADARSLAM_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = (dir / "child.out").string(), err = (dir / "child.err").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), STDOUT_FILENO);
    ::dup2(::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

/// Waits (up to 30 s) until `ready()`; false if the child exited first or time ran out.
template <typename Ready>
bool waitUntil(pid_t pid, Ready ready) {
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < deadline) {
    if (ready()) return true;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  return false;
}

/// SIGINT to the child; true if it ended by that signal.
bool interrupt(pid_t pid) {
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGINT;
}

/// Small simulated drives made once for the suite: `small` (6 scans of 64 x 256, a second to map)
/// and `wide` (4 scans of 64 x 3768 bins: returns up to 160 m, so a 1 cm grid is too large).
class HostileOutput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new radarslam::test::TempDir;
    CliResult r = runCli("simulate " + shellQuoted(small()) + " --scans 6 --azimuths 64 --bins 256", *root_);
    ASSERT_EQ(r.code, 0) << r.err;
    r = runCli("simulate " + shellQuoted(wide()) + " --scans 4 --azimuths 64", *root_);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }
  static fs::path small() { return *root_ / "small"; }
  static fs::path wide() { return *root_ / "wide"; }
  /// A private copy of the small dataset (for runs that could damage it).
  fs::path copyOfSmall(const std::string& name) const {
    const fs::path dst = tmp_ / name;
    fs::copy(small(), dst, fs::copy_options::recursive);
    return dst;
  }
  CliResult run(const std::string& args) const { return runCli(args, tmp_); }

  static radarslam::test::TempDir* root_;
  radarslam::test::TempDir tmp_;
};
radarslam::test::TempDir* HostileOutput::root_ = nullptr;

// --- class 1: -o replaces only what radarslam created ---------------------------------------

TEST_F(HostileOutput, MapSynthRefusesADirectoryThatIsNotAMapButReplacesItsOwnMap) {
  const fs::path dir = tmp_ / "notamap";
  fs::create_directories(dir / "keep");
  std::ofstream(dir / "keep" / "p.txt") << "precious\n";
  const auto before = snapshot(dir);
  expectOneLineError(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(dir)), dir.string());
  // --force never deletes the contents of a directory that is not a map.
  expectOneLineError(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(dir) + " --force"),
                     dir.string());
  EXPECT_EQ(snapshot(dir), before);

  // Its own map is what -o replaces, without --force.
  const fs::path map = tmp_ / "m";
  ASSERT_EQ(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(map) + " --max-keyframes 1").code,
            0);
  ASSERT_EQ(radarslam::loadMap(map).keyframes.size(), 1u);
  const CliResult r = run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(map) + " --every 0.2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(radarslam::loadMap(map).keyframes.size(), 1u);
  EXPECT_TRUE(leftovers(tmp_.path(), "m").empty());
}

TEST_F(HostileOutput, MapRefusesToWriteOverItsInputDataset) {
  const fs::path data = copyOfSmall("data");
  const auto before = snapshot(data);
  for (const fs::path& out : {data, data / "m", data / "gt"}) {
    SCOPED_TRACE(out.string());
    const CliResult r = run("map " + shellQuoted(data) + " -o " + shellQuoted(out) + " -q --force");
    expectOneLineError(r, out.string());
    EXPECT_NE(r.err.find("input"), std::string::npos) << r.err;
  }
  // A map around the dataset's parent: the output would contain the input.
  expectOneLineError(run("map-synth " + shellQuoted(data) + " -o " + shellQuoted(tmp_.path()) + " --force"),
                     "input");
  EXPECT_EQ(snapshot(data), before);
}

TEST_F(HostileOutput, AMapReplacesARegularFileOnlyWithForce) {
  const fs::path file = tmp_ / "notes.txt";
  std::ofstream(file) << "not a map\n";
  expectOneLineError(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(file)), file.string());
  EXPECT_EQ(readFileBytes(file), "not a map\n");
  const CliResult r = run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(file) + " --force");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(radarslam::loadMap(file).keyframes.size(), 0u);
}

TEST_F(HostileOutput, OtherCommandsRefuseOverlappingOutputs) {
  const fs::path map = tmp_ / "m";
  ASSERT_EQ(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(map)).code, 0);
  const auto map_before = snapshot(map);
  const fs::path est = tmp_ / "est.tum";
  fs::copy_file(small() / "gt" / "poses.tum", est);
  const auto data_before = snapshot(small());

  expectOneLineError(
      run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(small() / "t.tum") + " -q"), "input");
  expectOneLineError(
      run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(small() / "gt" / "poses.tum") + " -q"),
      "poses.tum");
  expectOneLineError(run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(tmp_ / "t.tum") +
                         " --eval-dir " + shellQuoted(small() / "eval") + " -q"),
                     "eval");
  expectOneLineError(run("localize " + shellQuoted(map) + " " + shellQuoted(small()) + " -o " +
                         shellQuoted(map / "poses.tum") + " -q"),
                     "input");
  expectOneLineError(run("export " + shellQuoted(map) + " -o " + shellQuoted(map)), map.string());
  expectOneLineError(run("export " + shellQuoted(map) + " -o " + shellQuoted(est)),
                     est.string());  // a file, not a directory
  expectOneLineError(
      run("eval " + shellQuoted(est) + " " + shellQuoted(small()) + " --json " + shellQuoted(est)),
      est.string());
  expectOneLineError(
      run("eval " + shellQuoted(est) + " " + shellQuoted(small()) + " --plot-dir " + shellQuoted(small())),
      "input");
  expectOneLineError(run("cart " + shellQuoted(small()) + " " + shellQuoted(small() / "x.png")), "input");
  expectOneLineError(run("convert " + shellQuoted(small()) + " " + shellQuoted(small() / "x.rawlog")),
                     "input");
  expectOneLineError(run("simulate " + shellQuoted(map) + " --scans 2 --force"), map.string());

  EXPECT_EQ(snapshot(map), map_before);
  EXPECT_EQ(snapshot(small()), data_before);
  EXPECT_EQ(readFileBytes(est), readFileBytes(small() / "gt" / "poses.tum"));
}

TEST_F(HostileOutput, SimulateReplacesOnlyAPreviousSimulation) {
  const fs::path other = tmp_ / "other";
  fs::create_directories(other / "radar");
  std::ofstream(other / "radar" / "mine.txt") << "not a scan\n";
  std::ofstream(other / "notes.txt") << "mine\n";
  const auto before = snapshot(other);
  expectOneLineError(run("simulate " + shellQuoted(other) + " --scans 2 --azimuths 64 --bins 256 --force"),
                     other.string());
  EXPECT_EQ(snapshot(other), before);

  const fs::path sim = tmp_ / "sim";
  ASSERT_EQ(run("simulate " + shellQuoted(sim) + " --scans 2 --azimuths 64 --bins 256").code, 0);
  expectOneLineError(run("simulate " + shellQuoted(sim) + " --scans 3 --azimuths 64 --bins 256"), "--force");
  const CliResult r = run("simulate " + shellQuoted(sim) + " --scans 3 --azimuths 64 --bins 256 --force");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(sim / "radar"), fs::directory_iterator()), 3);
  EXPECT_TRUE(leftovers(tmp_.path(), "sim").empty());
}

// --- class 2: special files are written in place ----------------------------------------------

TEST_F(HostileOutput, OdometryWritesIntoACharacterDeviceInPlace) {
  const fs::path dev = tmp_ / "null";
  if (::mknod(dev.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) != 0)
    GTEST_SKIP() << "mknod needs CAP_MKNOD: " << std::strerror(errno);
  const CliResult r = run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(dev) + " -q");
  ASSERT_EQ(r.code, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(::stat(dev.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  EXPECT_EQ(st.st_rdev, ::makedev(1, 3));
  EXPECT_TRUE(leftovers(tmp_.path(), "null").empty());
}

TEST_F(HostileOutput, OdometryWritesIntoAFifoInPlace) {
  const fs::path fifo = tmp_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so that the writer's open returns
  ASSERT_GE(reader, 0);
  const CliResult r = run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(fifo) + " -q");
  std::string got(65536, '\0');
  const ssize_t n = ::read(reader, got.data(), got.size());
  ::close(reader);
  ASSERT_EQ(r.code, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  ASSERT_GT(n, 0);
  EXPECT_EQ(lines(got.substr(0, static_cast<std::size_t>(n))), 7u);  // header + 6 poses through the pipe
}

// --- symbolic links are written through ---------------------------------------------------------

TEST_F(HostileOutput, OutputThroughASymlinkReplacesItsTarget) {
  const fs::path map = tmp_ / "real_map", link = tmp_ / "link";
  ASSERT_EQ(run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(map) + " --max-keyframes 1").code,
            0);
  fs::create_directory_symlink("real_map", link);
  const CliResult r = run("map-synth " + shellQuoted(small()) + " -o " + shellQuoted(link) + " --every 0.2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(link)) << "the link was replaced";
  EXPECT_GT(radarslam::loadMap(map).keyframes.size(), 1u);  // the map it points to is the new one

  const fs::path traj = tmp_ / "traj.tum", traj_link = tmp_ / "traj_link.tum";
  std::ofstream(traj) << "old\n";
  fs::create_symlink("traj.tum", traj_link);
  ASSERT_EQ(run("odometry " + shellQuoted(small()) + " -o " + shellQuoted(traj_link) + " -q").code, 0);
  EXPECT_TRUE(fs::is_symlink(traj_link));
  EXPECT_EQ(lines(readFileBytes(traj)), 7u);  // header + 6 poses
}

// --- class 8: everything is validated before the work, the swap is the last step ---------------

TEST_F(HostileOutput, BadOutputsFailBeforeTheRun) {
  const fs::path file = tmp_ / "file";
  std::ofstream(file) << "x\n";
  const auto check = [&](const std::string& args, const std::string& needle) {
    SCOPED_TRACE(args);
    const CliResult r = run(args);
    expectOneLineError(r, needle);  // one line: no "map: ..." / "odometry: ..." start of a run
  };
  check("odometry " + shellQuoted(small()) + " -o '' -q", "-o");
  check("map " + shellQuoted(small()) + " -o '' -q", "-o");
  check("map-synth " + shellQuoted(small()) + " -o ''", "-o");
  check("localize " + shellQuoted(tmp_ / "m") + " " + shellQuoted(small()) + " -o '' -q", "-o");
  check("convert " + shellQuoted(small()) + " ''", "OUT");
  check("odometry " + shellQuoted(small()) + " -o " + shellQuoted(file / "t.tum") + " -q",
        (file / "t.tum").string());
  check("map " + shellQuoted(small()) + " -o " + shellQuoted(file / "m") + " -q", (file / "m").string());
  check("odometry " + shellQuoted(small()) + " -o " + shellQuoted(tmp_ / "t.tum") + " --eval-dir " +
            shellQuoted(file) + " -q",
        file.string());
  check("map " + shellQuoted(small()) + " -o " + shellQuoted(tmp_ / "m") + " --grid-resolution 1e-6 -q",
        "--grid-resolution");
  EXPECT_FALSE(fs::exists(tmp_ / "m"));
  EXPECT_FALSE(fs::exists(tmp_ / "t.tum"));
  EXPECT_EQ(readFileBytes(file), "x\n");
}

TEST_F(HostileOutput, FailedGridExportLeavesThePreviousMapWhole) {
  const fs::path map = tmp_ / "m";
  ASSERT_EQ(run("map " + shellQuoted(small()) + " -o " + shellQuoted(map) + " -q --threads 1").code, 0);
  const auto before = snapshot(map);
  ASSERT_TRUE(before.count("grid.png") && before.count("trajectory.tum"));
  // Valid option, but the wide drive's 1 cm grid is too large: found after the run, before the swap.
  const CliResult r = run("map " + shellQuoted(wide()) + " -o " + shellQuoted(map) +
                          " -q --threads 1 --grid-resolution 0.01");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("too large"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(map), before) << "the previous map (with its products) must be untouched";
  EXPECT_TRUE(leftovers(tmp_.path(), "m").empty());
}

TEST_F(HostileOutput, GroundTruthThatDoesNotCoverTheScansIsBlamedOnTheGroundTruth) {
  const fs::path data = copyOfSmall("gt_elsewhere");
  {  // the same relative poses, 11.6 days later than the scans
    std::ifstream in(data / "gt" / "radar_odometry.csv");
    std::string header, line, text;
    std::getline(in, header);
    text = header + "\n";
    while (std::getline(in, line)) {
      std::vector<std::string> c;
      std::size_t pos = 0;
      for (std::size_t comma; (comma = line.find(',', pos)) != std::string::npos; pos = comma + 1)
        c.push_back(line.substr(pos, comma - pos));
      c.push_back(line.substr(pos));
      for (const int i : {0, 1, 8, 9}) c[i] = std::to_string(std::stoll(c[i]) + 1'000'000'000'000LL);
      for (std::size_t i = 0; i < c.size(); ++i) text += (i ? "," : "") + c[i];
      text += "\n";
    }
    in.close();
    std::ofstream(data / "gt" / "radar_odometry.csv") << text;
  }
  const std::string gt_file = (data / "gt" / "radar_odometry.csv").string();
  const fs::path traj = tmp_ / "t.tum";
  // The requested trajectory exists: exit 0, a warning naming the ground truth file.
  CliResult r = run("odometry " + shellQuoted(data) + " -o " + shellQuoted(traj) + " -q");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lines(readFileBytes(traj)), 7u);  // header + 6 poses
  EXPECT_NE((r.out + r.err).find("WARN: " + gt_file), std::string::npos) << r.out << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
  // The requested report cannot be made: exit 1, the error names the ground truth file.
  const fs::path eval = tmp_ / "eval";
  r = run("odometry " + shellQuoted(data) + " -o " + shellQuoted(traj) + " --eval-dir " + shellQuoted(eval) +
          " -q");
  EXPECT_EQ(r.code, 1) << r.err;
  const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
  EXPECT_EQ(last.rfind("radarslam: error: " + gt_file + ": ", 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(eval));
}

// --- class 10, output side: Ctrl-C leaves no temporary and no partial output -------------------

TEST_F(HostileOutput, InterruptedConvertLeavesNoTemporary) {
  // Scan 3 is a FIFO: convert refuses it (a one-line error) when it gets there. Ctrl-C as soon as
  // its temporary output appears usually lands before that; either way - interrupted, or ended by
  // the error - no temporary is left and the previous output is untouched. (Which one happens is
  // timing: the FIFO is no longer opened, so convert does not block on it.)
  const fs::path data = copyOfSmall("blocking");
  std::vector<fs::path> scans;
  for (const auto& e : fs::directory_iterator(data / "radar")) scans.push_back(e.path());
  std::sort(scans.begin(), scans.end());
  fs::remove(scans[3]);
  ASSERT_EQ(::mkfifo(scans[3].c_str(), 0644), 0);
  const fs::path out = tmp_ / "x.rawlog";
  std::ofstream(out) << "previous\n";
  const pid_t pid = start({"convert", data.string(), out.string()}, tmp_.path());
  int status = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  bool ended = false;
  while (Clock::now() < deadline && leftovers(tmp_.path(), "x.rawlog").empty())
    if ((ended = ::waitpid(pid, &status, WNOHANG) == pid)) break;
  if (!ended) {
    ::kill(pid, SIGINT);
    ::waitpid(pid, &status, 0);
  }
  const std::string err = readFileBytes(tmp_ / "child.err");
  const bool interrupted = WIFSIGNALED(status) && WTERMSIG(status) == SIGINT;
  const bool refused = WIFEXITED(status) && WEXITSTATUS(status) == 1 &&
                       err.find("not a regular file (a FIFO)") != std::string::npos;
  EXPECT_TRUE(interrupted || refused) << err;
  EXPECT_TRUE(leftovers(tmp_.path(), "x.rawlog").empty());
  EXPECT_EQ(readFileBytes(out), "previous\n");
}

TEST_F(HostileOutput, InterruptedExportLeavesNoPartialSetOfFiles) {
  const fs::path map = tmp_ / "m", out = tmp_ / "exports";
  ASSERT_EQ(run("map-synth " + shellQuoted(wide()) + " -o " + shellQuoted(map) + " --every 0.1").code, 0);
  // A fine grid: the export takes about a second; interrupted as soon as it writes anything.
  const pid_t pid = start({"export", map.string(), "-o", out.string(), "--resolution", "0.05"}, tmp_.path());
  ASSERT_TRUE(waitUntil(pid, [&] { return fs::exists(out) || !leftovers(tmp_.path(), "exports").empty(); }));
  EXPECT_TRUE(interrupt(pid));
  EXPECT_FALSE(fs::exists(out)) << "a partial export was left";
  EXPECT_TRUE(leftovers(tmp_.path(), "exports").empty());
}

TEST_F(HostileOutput, InterruptedSimulateLeavesNothingAndTheNextRunNeedsNoForce) {
  const fs::path sim = tmp_ / "sim";
  const pid_t pid =
      start({"simulate", sim.string(), "--scans", "400", "--azimuths", "64", "--bins", "256"}, tmp_.path());
  ASSERT_TRUE(waitUntil(pid, [&] { return fs::exists(sim) || !leftovers(tmp_.path(), "sim").empty(); }));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // some scans written
  EXPECT_TRUE(interrupt(pid));
  EXPECT_FALSE(fs::exists(sim));
  EXPECT_TRUE(leftovers(tmp_.path(), "sim").empty());
  const CliResult r = run("simulate " + shellQuoted(sim) + " --scans 2 --azimuths 64 --bins 256");
  EXPECT_EQ(r.code, 0) << r.err;
}

}  // namespace
