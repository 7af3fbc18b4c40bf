#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "temp_dir.h"

using namespace radarslam;

static std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(AtomicFile, FailedWriteLeavesPreviousContentAndNoTemporaries) {
  test::TempDir dir;
  const auto target = dir / "out.txt";
  writeTextAtomically(target, "old");
  EXPECT_THROW(writeFileAtomically(target,
                                   [](const std::filesystem::path& tmp) {
                                     std::ofstream(tmp) << "half-writ";
                                     throw InputError("x", "simulated crash");
                                   }),
               InputError);
  EXPECT_EQ(slurp(target), "old");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) (void)e, ++files;
  EXPECT_EQ(files, 1);
  writeTextAtomically(dir / "sub/dir/new.txt", "new");
  EXPECT_EQ(slurp(dir / "sub/dir/new.txt"), "new");
}
