#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "file_contents.h"
#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "temp_dir.h"

using namespace radarslam;

using radarslam::test::readFileBytes;

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
  EXPECT_EQ(readFileBytes(target), "old");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) (void)e, ++files;
  EXPECT_EQ(files, 1);
  writeTextAtomically(dir / "sub/dir/new.txt", "new");
  EXPECT_EQ(readFileBytes(dir / "sub/dir/new.txt"), "new");
}
