#include "core/io/files.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "dampbound/physics/error.hpp"

namespace dampbound {
namespace {

TEST(AtomicWrite, WholeOrNothing) {
  const std::string path = "io_test_out.txt";
  write_file_atomic(path, [](std::ostream& o) { o << "hello\n"; });
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "hello\n");
  EXPECT_THROW(write_file_atomic("/nonexistent-dir/x.csv", [](std::ostream& o) { o << 1; }),
               InputError);
  EXPECT_THROW(check_writable("/nonexistent-dir/x.csv"), InputError);
  ::unlink(path.c_str());
}

std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "dampbound_io_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

size_t entries(const std::string& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicWrite, RefusesWhatIsNotARegularFile) {
  const std::string dir = fresh_dir("devices");
  for (const std::string& path : {std::string("/dev/null"), std::string("/dev/full"), dir}) {
    EXPECT_THROW(check_writable(path), InputError) << path;
    EXPECT_THROW(write_file_atomic(path, [](std::ostream& o) { o << "x"; }), InputError) << path;
    EXPECT_THROW(write_file_bytes(path, "x"), InputError) << path;
    EXPECT_THROW(write_durably(path, [](std::FILE* f) { std::fputs("x", f); }), InputError)
        << path;
  }
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));  // still the device
  EXPECT_EQ(entries(dir), 0u);
}

TEST(AtomicWrite, AnUncommittedOutputLeavesNothing) {
  // A failure (or a kill) before the rename leaves no PATH and no temporary beside it.
  const std::string dir = fresh_dir("uncommitted");
  {
    PendingOutput out(dir + "/a.csv", [](int fd) { write_all(fd, "half", "a.csv"); });
  }
  EXPECT_EQ(entries(dir), 0u);
  EXPECT_THROW(write_file_atomic(dir + "/b.csv",
                                 [](std::ostream& o) {
                                   o << "part";
                                   throw InputError("stop");
                                 }),
               InputError);
  EXPECT_EQ(entries(dir), 0u);
  PendingOutput done(dir + "/c.csv", [](int fd) { write_all(fd, "whole\n", "c.csv"); });
  EXPECT_EQ(entries(dir), 0u);  // not in place before commit
  done.commit();
  EXPECT_EQ(read_file_text(dir + "/c.csv"), "whole\n");
  EXPECT_EQ(entries(dir), 1u);
}

TEST(AtomicWrite, FollowsALinkToARegularFile) {
  const std::string dir = fresh_dir("link");
  write_file_bytes(dir + "/target.csv", "old");
  std::filesystem::create_symlink("target.csv", dir + "/link.csv");
  write_file_bytes(dir + "/link.csv", "new");
  EXPECT_TRUE(std::filesystem::is_symlink(dir + "/link.csv"));
  EXPECT_EQ(read_file_text(dir + "/target.csv"), "new");
}

TEST(ReadFile, RefusesDirectoriesDevicesFifosAndHugeFiles) {
  const std::string dir = fresh_dir("inputs");
  EXPECT_THROW(read_file_text(dir), InputError);
  EXPECT_THROW(read_file_text("/dev/zero"), InputError);  // would never end
  ASSERT_EQ(::mkfifo((dir + "/fifo").c_str(), 0600), 0);
  EXPECT_THROW(read_file_text(dir + "/fifo"), InputError);  // would block
  write_file_bytes(dir + "/ten", "0123456789");
  EXPECT_EQ(read_file_text(dir + "/ten", 10), "0123456789");
  try {
    read_file_text(dir + "/ten", 9);
    ADD_FAILURE() << "a file over the limit was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than the limit of 9 bytes"), std::string::npos);
  }
}

}  // namespace
}  // namespace dampbound
