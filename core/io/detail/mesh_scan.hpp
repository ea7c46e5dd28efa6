#pragma once
// The cursor the mesh readers share (private to core, not installed): whitespace-separated
// tokens with line numbers for text, fixed-size little-endian values with byte offsets for
// binary, and one-line errors "NAME:LINE: message" or "NAME: byte N: message" (InputError).
// Reads a caller's buffer; never reads past its end, whatever the content.
#include <cstddef>
#include <cstring>
#include <optional>
#include <string>

namespace dampbound {

/// A mesh file's number: the whole token, decimal (no mesh format writes the hexadecimal
/// floats strtod also reads), finite. Underflow is a number: 1e-310 is a subnormal double,
/// 1e-400 rounds to 0. Shared by every mesh reader (MeshScan::number, the OBJ reader).
std::optional<double> finite_number(const std::string& token);

class MeshScan {
 public:
  /// `data` must outlive the scanner; `name` is used in messages only.
  MeshScan(const char* data, size_t size, std::string name);

  /// Skip '#' comments to the end of the line in text reads (TetGen).
  void set_comments(bool on) { comments_ = on; }

  /// True when only whitespace (and comments) is left.
  bool at_end();
  /// The next token; fails at the end of the data with "unexpected end of file (WHAT)".
  std::string word(const char* what);
  /// The next token as an integer / a finite number; fails naming `what` otherwise.
  long long integer(const char* what);
  double number(const char* what);
  /// An integer in [lo, hi].
  long long integer_in(const char* what, long long lo, long long hi);
  /// The rest of the current line (without the newline), and moves to the next line.
  std::string rest_of_line();
  /// Skips one newline (and spaces before it) if it is next: the separator between an ASCII
  /// header and binary data.
  void skip_newline();

  /// Reads a T stored in the file's bytes (native little-endian, as Gmsh writes it).
  template <class T>
  T binary(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  /// Moves past the next occurrence of `marker`; fails if there is none.
  void skip_past(const std::string& marker);

  /// Text position for messages: the current line, or the current byte offset after
  /// set_binary(true).
  void set_binary(bool on) { binary_ = on; }
  long long where() const { return binary_ ? static_cast<long long>(pos_) : line_; }
  /// where() of the next token: skips whitespace first in text mode (not in binary mode,
  /// where such bytes are data).
  long long mark() {
    if (!binary_) skip_space();
    return where();
  }
  bool binary_mode() const { return binary_; }
  size_t remaining() const { return size_ - pos_; }
  const std::string& name() const { return name_; }

  /// "NAME:LINE" or "NAME: byte N" for a position from where().
  std::string location(long long where) const;
  [[noreturn]] void fail(const std::string& msg) const;
  [[noreturn]] void fail_at(long long where, const std::string& msg) const;

 private:
  void skip_space();
  void need(size_t bytes, const char* what) const;

  const char* data_;
  size_t size_;
  size_t pos_ = 0;
  long long line_ = 1;
  std::string name_;
  bool comments_ = false;
  bool binary_ = false;
};

/// `count` records from a file with `remaining` bytes left, each at least `min_bytes` long:
/// a count the data cannot hold is an error (so no reader allocates from a corrupt header).
void check_count(MeshScan& scan, long long count, size_t min_bytes, const char* what);

}  // namespace dampbound
