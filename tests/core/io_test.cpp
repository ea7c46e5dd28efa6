#include "core/io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace dampbound {
namespace {

TEST(Format, ShortestRoundTripAndNoNaN) {
  EXPECT_EQ(format_number(0.05), "0.05");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(std::nan("")), "inf");
  EXPECT_EQ(json_number(std::nan("")), "null");
  EXPECT_EQ(json_string("a\"b\n"), "\"a\\\"b\\n\"");
}

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

}  // namespace
}  // namespace dampbound
