#include "core/io/detail/mesh_scan.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "core/io/format.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

MeshScan::MeshScan(const char* data, size_t size, std::string name)
    : data_(data), size_(size), name_(std::move(name)) {}

std::string MeshScan::location(long long where) const {
  return binary_ ? name_ + ": byte " + std::to_string(where) : name_ + ":" + std::to_string(where);
}

void MeshScan::fail(const std::string& msg) const {
  fail_at(where(), msg);
}

void MeshScan::fail_at(long long where, const std::string& msg) const {
  throw InputError(location(where) + ": " + msg);
}

void MeshScan::need(size_t bytes, const char* what) const {
  if (size_ - pos_ < bytes)
    fail(std::string("truncated file: ") + std::to_string(bytes) + " bytes of " + what +
         " expected, " + std::to_string(size_ - pos_) + " left");
}

void MeshScan::skip_space() {
  while (pos_ < size_) {
    const char c = data_[pos_];
    if (c == '\n') {
      ++line_;
    } else if (comments_ && c == '#') {
      while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
      continue;
    } else if (!std::isspace(static_cast<unsigned char>(c))) {
      return;
    }
    ++pos_;
  }
}

bool MeshScan::at_end() {
  skip_space();
  return pos_ >= size_;
}

std::string MeshScan::word(const char* what) {
  skip_space();
  if (pos_ >= size_) fail(std::string("unexpected end of file (") + what + " expected)");
  const size_t start = pos_;
  while (pos_ < size_ && !std::isspace(static_cast<unsigned char>(data_[pos_])) &&
         !(comments_ && data_[pos_] == '#'))
    ++pos_;
  return std::string(data_ + start, pos_ - start);
}

long long MeshScan::integer(const char* what) {
  const std::string t = word(what);
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  // The whole token: a NUL inside it would end strtoll's reading early.
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE)
    fail(std::string(what) + ": '" + printable(t.substr(0, 40)) + "' is not an integer");
  return v;
}

long long MeshScan::integer_in(const char* what, long long lo, long long hi) {
  const long long v = integer(what);
  if (v < lo || v > hi)
    fail(std::string(what) + " " + std::to_string(v) + " is outside " + std::to_string(lo) + ".." +
         std::to_string(hi));
  return v;
}

std::optional<double> finite_number(const std::string& t) {
  if (t.empty() || t.find_first_of("xX") != std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double v = c_strtod(t.c_str(), &end);
  // The whole token: a NUL inside it would end strtod's reading early.
  if (end != t.c_str() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

double MeshScan::number(const char* what) {
  const std::string t = word(what);
  const std::optional<double> v = finite_number(t);
  if (!v) fail(std::string(what) + ": '" + printable(t.substr(0, 40)) + "' is not a finite number");
  return *v;
}

std::string MeshScan::rest_of_line() {
  const size_t start = pos_;
  while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
  std::string out(data_ + start, pos_ - start);
  if (pos_ < size_) {
    ++pos_;
    ++line_;
  }
  if (!out.empty() && out.back() == '\r') out.pop_back();
  return out;
}

void MeshScan::skip_newline() {
  while (pos_ < size_ && (data_[pos_] == ' ' || data_[pos_] == '\r' || data_[pos_] == '\t')) ++pos_;
  if (pos_ < size_ && data_[pos_] == '\n') {
    ++pos_;
    ++line_;
  }
}

void MeshScan::skip_past(const std::string& marker) {
  for (size_t p = pos_; p + marker.size() <= size_; ++p)
    if (std::memcmp(data_ + p, marker.data(), marker.size()) == 0) {
      for (size_t q = pos_; q < p + marker.size(); ++q) line_ += data_[q] == '\n';
      pos_ = p + marker.size();
      return;
    }
  fail("truncated file: no " + marker);
}

void check_count(MeshScan& scan, long long count, size_t min_bytes, const char* what) {
  if (count < 0 ||
      static_cast<unsigned long long>(count) > scan.remaining() / std::max<size_t>(min_bytes, 1))
    scan.fail(std::string("the file is too short for ") + std::to_string(count) + " " + what);
}

}  // namespace dampbound
