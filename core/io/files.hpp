#pragma once
// Input and output files (docs/hardening.md): every output is written whole or not at all,
// only as a regular file, with every write checked; every input is a regular file of bounded
// size. Number formatting that never prints NaN.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>

namespace dampbound {

/// Largest scene file read (bytes): a scene of 1e5 explicit nodes is about 5 MB.
constexpr std::uint64_t kMaxSceneBytes = 16u << 20;
/// Largest file read otherwise (meshes, sweep CSVs, journals, settings), bytes.
constexpr std::uint64_t kMaxInputBytes = 1u << 30;

/// An output file finished under a temporary name and not yet in place. The one writer every
/// output goes through: it refuses a PATH that exists and is not a regular file (a directory,
/// a device such as /dev/null, a FIFO), writes into an anonymous file in PATH's directory
/// (O_TMPFILE; a uniquely named PATH.tmp.<pid> where the file system has none), checks every
/// write, fsyncs, and on commit() renames onto PATH. Destroyed uncommitted, it leaves nothing
/// behind. Throws InputError naming PATH on any failure (disk full included).
class PendingOutput {
 public:
  /// Writes the whole file through `fill`, which writes to the file descriptor it is given.
  PendingOutput(const std::string& path, const std::function<void(int fd)>& fill);
  ~PendingOutput();
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;
  /// Moves the file into place (then fsyncs the directory).
  void commit();

 private:
  std::string path_, tmp_;
  int fd_ = -1;
};

/// Writes through `write` to `fd` (a PendingOutput's), checking every write.
void write_stream(int fd, const std::string& path,
                  const std::function<void(std::ostream&)>& write);
/// Writes through `write` and puts the file in place (PendingOutput).
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write);
/// The same through a buffered FILE* (for the large sweep CSVs).
void write_durably(const std::string& path, const std::function<void(std::FILE*)>& fill);
/// The same for bytes already in memory (encoded images).
void write_file_bytes(const std::string& path, std::string_view bytes);
/// Writes all of `bytes` to `fd`, retrying short writes; InputError naming `path` otherwise.
void write_all(int fd, std::string_view bytes, const std::string& path);

/// fsyncs the directory that holds PATH (so that a rename or unlink in it is durable).
void sync_directory(const std::string& path);

/// Fails early (InputError naming the path) when PATH cannot become a regular file: its
/// directory is missing or not writable, or PATH is a directory, a device or a FIFO.
void check_writable(const std::string& path);

/// Fails (InputError naming the path) unless PATH is a regular file: a directory, a FIFO (which
/// would block) or a device (/dev/zero never ends) is refused before it is opened.
void check_regular_input(const std::string& path);

/// The whole file as bytes; InputError naming the path when it is not a regular file, larger
/// than `max_bytes`, or cannot be read.
std::string read_file_text(const std::string& path, std::uint64_t max_bytes = kMaxInputBytes);

/// TEXT with control characters (newline, escape, ...) shown as \xNN: safe on one terminal line.
std::string printable(std::string_view text);

/// Shortest decimal (15 to 17 digits) that reads back as the same double; non-finite values print as "inf" ("-inf").
std::string format_number(double x);

/// JSON number, or null when not finite (JSON has no inf or NaN).
std::string json_number(double x);

/// JSON string literal with escapes.
std::string json_string(const std::string& s);

}  // namespace dampbound
