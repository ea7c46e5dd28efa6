#include "core/sweep/journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <unordered_set>

#include "core/io/format.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

std::uint32_t fnv1a32(const char* p, size_t n) {
  std::uint32_t h = 2166136261u;
  for (size_t k = 0; k < n; ++k) {
    h ^= static_cast<unsigned char>(p[k]);
    h *= 16777619u;
  }
  return h;
}

char outcome_code(Outcome o) {
  switch (o) {
    case Outcome::restored:
      return 'r';
    case Outcome::diverged:
      return 'd';
    case Outcome::not_restored:
      return 'n';
    case Outcome::settled:
      return 's';
    case Outcome::not_settled:
      return 'u';
    case Outcome::running:
      break;
  }
  return '?';
}

/// Whether a result needs the band fields (SPEC 8) written out: under the first-entry rule
/// they follow from the outcome (first entry = the iteration of a restore, none otherwise),
/// so first-entry journals keep their old lines.
bool band_implied(const TrialResult& r) {
  const int implied = r.outcome == Outcome::restored ? r.iterations : 0;
  return r.first_entry == implied && r.left_at == 0 && r.settled_at == 0;
}

/// A journal line: the body, a space, its 8-hex-digit FNV-1a checksum and a newline.
std::string with_checksum(const char* body, int n) {
  char sum[16];
  c_snprintf(sum, sizeof sum, " %08" PRIx32 "\n", fnv1a32(body, static_cast<size_t>(n)));
  return std::string(body, static_cast<size_t>(n)) + sum;
}

/// Whether a line (without its newline) ends in the right checksum of what precedes it.
bool checksum_ok(const std::string& line) {
  const size_t space = line.find_last_of(' ');
  if (space == std::string::npos || line.size() - space != 9) return false;
  char* end = nullptr;
  const unsigned long sum = std::strtoul(line.c_str() + space + 1, &end, 16);
  return *end == '\0' && sum == fnv1a32(line.data(), space);
}

}  // namespace

std::string journal_line(const JournalEntry& e) {
  const TrialResult& r = e.result;
  char body[256];
  int n = c_snprintf(body, sizeof body, "%" PRIu32 " %c %d %a %lld %lld %lld %lld", e.cls,
                        outcome_code(r.outcome), r.iterations, r.max_displacement, r.violations,
                        r.unstabilisable, r.clamped, r.zero_length_springs);
  if (!band_implied(r))  // " b FIRST LEFT SETTLED": the settled rule's band fields
    n += c_snprintf(body + n, sizeof body - static_cast<size_t>(n), " b %d %d %d",
                       r.first_entry, r.left_at, r.settled_at);
  return with_checksum(body, n);
}

std::optional<JournalEntry> parse_journal_line(const std::string& line) {
  if (!checksum_ok(line)) return std::nullopt;
  char code = 0;
  char disp[64];
  JournalEntry x;
  TrialResult& r = x.result;
  int used = 0;
  if (std::sscanf(line.c_str(), "%" SCNu32 " %c %d %63s %lld %lld %lld %lld%n", &x.cls, &code,
                  &r.iterations, disp, &r.violations, &r.unstabilisable, &r.clamped,
                  &r.zero_length_springs, &used) != 8)
    return std::nullopt;
  const bool band = line.compare(static_cast<size_t>(used), 3, " b ") == 0;
  if (band && std::sscanf(line.c_str() + used, " b %d %d %d", &r.first_entry, &r.left_at,
                          &r.settled_at) != 3)
    return std::nullopt;
  char* end = nullptr;
  r.max_displacement = c_strtod(disp, &end);
  // A line with a good checksum can still be forged or come from a broken build: what no
  // run can give is refused (counts are node-steps >= 0; only a diverged trial ends at a
  // non-finite displacement).
  if (*end != '\0' || r.iterations < 0 || r.violations < 0 || r.unstabilisable < 0 ||
      r.clamped < 0 || r.zero_length_springs < 0 || r.max_displacement < 0 ||
      (!std::isfinite(r.max_displacement) && code != 'd'))
    return std::nullopt;
  switch (code) {
    case 'r':
      r.outcome = Outcome::restored;
      break;
    case 'd':
      r.outcome = Outcome::diverged;
      break;
    case 'n':
      r.outcome = Outcome::not_restored;
      break;
    case 's':
      r.outcome = Outcome::settled;
      break;
    case 'u':
      r.outcome = Outcome::not_settled;
      break;
    default:
      return std::nullopt;
  }
  if (!band && r.outcome == Outcome::restored) r.first_entry = r.iterations;
  return x;
}

std::string journal_time_line(const JournalTime& t) {
  char body[128];
  const int n = c_snprintf(body, sizeof body, "t %d %.3f %.3f %" PRIu64, t.run, t.wall_s,
                              t.cpu_s, t.classes);
  return with_checksum(body, n);
}

std::optional<JournalTime> parse_journal_time_line(const std::string& line) {
  if (line.rfind("t ", 0) != 0 || !checksum_ok(line)) return std::nullopt;
  JournalTime x;
  const CNumericScope c;  // %lf reads "12.5" whatever the host's locale
  if (std::sscanf(line.c_str(), "t %d %lf %lf %" SCNu64, &x.run, &x.wall_s, &x.cpu_s, &x.classes) !=
          4 ||
      x.run < 1 || !(x.wall_s >= 0) || !(x.cpu_s >= 0))
    return std::nullopt;
  return x;
}

JournalContents read_journal(const std::string& path, const std::string& header,
                             std::uint64_t classes) {
  check_regular_input(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the journal");
  JournalContents jc;
  std::string line;
  // Empty, or killed while its header was being written: nothing was done, start afresh.
  if (!std::getline(in, line) || (in.eof() && header.compare(0, line.size(), line) == 0))
    return jc;
  if (line != header)
    throw InputError("--resume: " + path +
                     " belongs to another sweep or another shard (its first line is not '" +
                     header + "'); remove it to start over");
  jc.valid_bytes = line.size() + 1;
  std::unordered_set<std::uint32_t> seen;
  std::map<int, JournalTime> times;  // each run's last record
  // Only whole lines (ending in '\n') with a good checksum count; the first bad one ends
  // the valid prefix (what follows it was written after the last completed sync).
  while (std::getline(in, line)) {
    if (const auto t = in.eof() ? std::nullopt : parse_journal_time_line(line)) {
      times[t->run] = *t;
      jc.valid_bytes += line.size() + 1;
      continue;
    }
    const auto parsed = in.eof() ? std::nullopt : parse_journal_line(line);
    if (!parsed) {
      ++jc.dropped_lines;
      break;
    }
    const JournalEntry& e = *parsed;
    if (e.cls >= classes)
      throw InputError(path + ": class " + std::to_string(e.cls) + " is not in this sweep");
    jc.valid_bytes += line.size() + 1;
    if (seen.insert(e.cls).second)
      jc.entries.push_back(e);
    else
      ++jc.dropped_lines;
  }
  while (std::getline(in, line)) ++jc.dropped_lines;
  for (const auto& [run, t] : times) {
    jc.runs = std::max(jc.runs, run);
    jc.wall_s += t.wall_s;
    jc.cpu_s += t.cpu_s;
    jc.timed_classes += t.classes;
  }
  return jc;
}

Journal::Journal(std::string path, const std::string& header, std::uint64_t resume_valid_bytes)
    : path_(std::move(path)) {
  if (resume_valid_bytes > 0) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0 || ::ftruncate(fd_, static_cast<off_t>(resume_valid_bytes)) != 0 ||
        ::lseek(fd_, 0, SEEK_END) < 0) {
      const int err = errno;
      if (fd_ >= 0) ::close(fd_);
      throw InputError(path_ + ": cannot reopen the journal (" + std::strerror(err) + ")");
    }
    ::fsync(fd_);
    return;
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(path_ + ": cannot create the journal (" + std::strerror(errno) + ")");
  try {
    write_all(fd_, header + "\n", path_);
    if (::fsync(fd_) != 0)
      throw InputError(path_ + ": cannot sync the journal (" + std::strerror(errno) + ")");
  } catch (...) {  // a full disk: no journal is left behind to block the next run
    ::close(fd_);
    ::unlink(path_.c_str());
    throw;
  }
  sync_directory(path_);
}

Journal::~Journal() {
  if (fd_ >= 0) {
    try {
      sync();
    } catch (...) {
    }
    ::close(fd_);
  }
}

void Journal::add(const JournalEntry& e) {
  buffer_ += journal_line(e);
}

void Journal::add_time(const JournalTime& t) {
  buffer_ += journal_time_line(t);
}

void Journal::sync() {
  if (fd_ < 0 || buffer_.empty()) return;
  write_all(fd_, buffer_, path_);
  buffer_.clear();
  if (::fdatasync(fd_) != 0)
    throw InputError(path_ + ": cannot sync the journal (" + std::strerror(errno) + ")");
}

void Journal::remove() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  buffer_.clear();
  ::unlink(path_.c_str());
  sync_directory(path_);
}

}  // namespace dampbound
