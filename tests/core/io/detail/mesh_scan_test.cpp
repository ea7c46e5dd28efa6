// The mesh readers' cursor (core/io/detail/mesh_scan.hpp): tokens and line numbers, number
// scanning on its edge cases, comments, binary reads with byte offsets, and counts the data
// cannot hold.
#include "core/io/detail/mesh_scan.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

/// The number `text` scans as, or the message it fails with.
std::string scan_number(const std::string& text) {
  MeshScan s(text.data(), text.size(), "f");
  try {
    return std::to_string(s.number("x"));
  } catch (const InputError& e) {
    return e.what();
  }
}
std::string scan_integer(const std::string& text) {
  MeshScan s(text.data(), text.size(), "f");
  try {
    return std::to_string(s.integer("n"));
  } catch (const InputError& e) {
    return e.what();
  }
}

TEST(MeshScan, WordsAndLineNumbers) {
  const std::string text = "  a bb\n\n\tccc \r\n d";
  MeshScan s(text.data(), text.size(), "f.txt");
  EXPECT_EQ(s.where(), 1);
  EXPECT_EQ(s.word("w"), "a");
  EXPECT_EQ(s.word("w"), "bb");
  EXPECT_EQ(s.mark(), 3);  // skips the blank line to the next token
  EXPECT_EQ(s.word("w"), "ccc");
  EXPECT_EQ(s.rest_of_line(), " ");  // the '\r' of a CRLF line is dropped
  EXPECT_EQ(s.where(), 4);
  EXPECT_FALSE(s.at_end());
  EXPECT_EQ(s.word("w"), "d");
  EXPECT_TRUE(s.at_end());
  EXPECT_EQ(test::input_error([&] { s.word("the last node"); }),
            "f.txt:4: unexpected end of file (the last node expected)");
}

TEST(MeshScan, Numbers) {
  EXPECT_EQ(scan_number("1.5"), std::to_string(1.5));
  EXPECT_EQ(scan_number("-2e3"), std::to_string(-2000.0));
  EXPECT_EQ(scan_number("+.25"), std::to_string(0.25));
  EXPECT_EQ(scan_number("7"), std::to_string(7.0));
  EXPECT_EQ(scan_number("1.5e"), "f:1: x: '1.5e' is not a finite number");
  EXPECT_EQ(scan_number("1,5"), "f:1: x: '1,5' is not a finite number");
  EXPECT_EQ(scan_number("nan"), "f:1: x: 'nan' is not a finite number");
  EXPECT_EQ(scan_number("inf"), "f:1: x: 'inf' is not a finite number");
  EXPECT_EQ(scan_number("-Infinity"), "f:1: x: '-Infinity' is not a finite number");
  EXPECT_EQ(scan_number("1e400"), "f:1: x: '1e400' is not a finite number");  // overflows
  // Underflow is a number: a subnormal, and one that rounds to zero.
  EXPECT_EQ(scan_number("1e-310"), std::to_string(1e-310));
  EXPECT_EQ(scan_number("-1e-400"), std::to_string(-0.0));
  // Hexadecimal floats are not a mesh format's numbers; a NUL inside a token is no end.
  EXPECT_EQ(scan_number("0x1p3"), "f:1: x: '0x1p3' is not a finite number");
  EXPECT_EQ(scan_number(std::string("1.5\0" "7", 5)), "f:1: x: '1.5\\x007' is not a finite number");
  // A long token is quoted to 40 characters.
  EXPECT_EQ(scan_number(std::string(50, 'z')),
            "f:1: x: '" + std::string(40, 'z') + "' is not a finite number");
  EXPECT_EQ(scan_number("\n\n"), "f:3: unexpected end of file (x expected)");
}

TEST(MeshScan, Integers) {
  EXPECT_EQ(scan_integer("42"), "42");
  EXPECT_EQ(scan_integer("-7"), "-7");
  EXPECT_EQ(scan_integer("+3"), "3");
  EXPECT_EQ(scan_integer("007"), "7");  // base 10, not octal
  EXPECT_EQ(scan_integer("9223372036854775807"), "9223372036854775807");
  EXPECT_EQ(scan_integer("9223372036854775808"),
            "f:1: n: '9223372036854775808' is not an integer");
  EXPECT_EQ(scan_integer("1.0"), "f:1: n: '1.0' is not an integer");
  EXPECT_EQ(scan_integer("0x10"), "f:1: n: '0x10' is not an integer");
  EXPECT_EQ(scan_integer("1e3"), "f:1: n: '1e3' is not an integer");
  EXPECT_EQ(scan_integer(std::string("12\0" "3", 4)), "f:1: n: '12\\x003' is not an integer");
  const std::string text = "5 0 11";
  MeshScan s(text.data(), text.size(), "f");
  EXPECT_EQ(s.integer_in("count", 0, 10), 5);
  EXPECT_EQ(s.integer_in("count", 0, 10), 0);
  EXPECT_EQ(test::input_error([&] { s.integer_in("count", 0, 10); }), "f:1: count 11 is outside 0..10");
}

TEST(MeshScan, CommentsOnlyWhenAsked) {
  const std::string text = "1 # two\n# a line\n3#4\n";
  MeshScan plain(text.data(), text.size(), "f");
  EXPECT_EQ(plain.word("w"), "1");
  EXPECT_EQ(plain.word("w"), "#");
  MeshScan tetgen(text.data(), text.size(), "f");
  tetgen.set_comments(true);
  EXPECT_EQ(tetgen.integer("a"), 1);
  EXPECT_EQ(tetgen.integer("b"), 3);  // a comment ends a token
  EXPECT_EQ(tetgen.where(), 3);
  EXPECT_TRUE(tetgen.at_end());
}

TEST(MeshScan, BinaryValuesAndByteOffsets) {
  std::string data = "$Nodes\n";
  const std::int32_t n = 3;
  const double x = -1.25;
  data.append(reinterpret_cast<const char*>(&n), sizeof n);
  data.append(reinterpret_cast<const char*>(&x), sizeof x);
  data.append("\x01\x02", 2);
  MeshScan s(data.data(), data.size(), "b.msh");
  EXPECT_EQ(s.word("section"), "$Nodes");
  s.skip_newline();
  s.set_binary(true);
  EXPECT_TRUE(s.binary_mode());
  EXPECT_EQ(s.where(), 7);
  EXPECT_EQ(s.binary<std::int32_t>("count"), 3);
  EXPECT_EQ(s.binary<double>("x"), -1.25);
  EXPECT_EQ(s.remaining(), 2u);
  EXPECT_EQ(s.mark(), 19);  // no whitespace skipping in binary mode
  EXPECT_EQ(test::input_error([&] { s.binary<double>("y"); }),
            "b.msh: byte 19: truncated file: 8 bytes of y expected, 2 left");
  EXPECT_EQ(s.location(5), "b.msh: byte 5");
  s.set_binary(false);
  EXPECT_EQ(s.location(5), "b.msh:5");
}

TEST(MeshScan, SkipPastCountsTheLinesItCrosses) {
  const std::string text = "a\nb\n$EndNodes\nc";
  MeshScan s(text.data(), text.size(), "f");
  s.skip_past("$EndNodes");
  EXPECT_EQ(s.where(), 3);
  EXPECT_EQ(s.word("w"), "c");
  EXPECT_EQ(s.where(), 4);
  EXPECT_EQ(test::input_error([&] { s.skip_past("$EndElements"); }),
            "f:4: truncated file: no $EndElements");
}

TEST(MeshScan, CountsTheDataCannotHold) {
  const std::string text = "0123456789";  // 10 bytes left
  MeshScan s(text.data(), text.size(), "f");
  EXPECT_EQ(test::input_error([&] { check_count(s, 5, 2, "nodes"); }), "");
  EXPECT_EQ(test::input_error([&] { check_count(s, 6, 2, "nodes"); }),
            "f:1: the file is too short for 6 nodes");
  EXPECT_EQ(test::input_error([&] { check_count(s, -1, 2, "nodes"); }),
            "f:1: the file is too short for -1 nodes");
  EXPECT_EQ(test::input_error([&] { check_count(s, 10, 0, "points"); }), "");  // min 0 counts as 1
}

}  // namespace
}  // namespace dampbound
