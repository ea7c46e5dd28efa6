#pragma once
// A file in memory (memfd) with a path, for fuzz targets whose readers take a path.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace dampbound::fuzz {

/// Holds the fuzzer's bytes in a memfd reachable as /proc/self/fd/N (a regular file).
class MemoryFile {
 public:
  MemoryFile() : fd_(::memfd_create("dampbound-fuzz", 0)) {}
  ~MemoryFile() { ::close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  /// Replaces the content with `size` bytes at `data`; returns the path, "" on failure.
  std::string hold(const std::uint8_t* data, std::size_t size) {
    if (fd_ < 0 || ::ftruncate(fd_, 0) != 0) return "";
    std::size_t done = 0;
    while (done < size) {
      const ssize_t w = ::pwrite(fd_, data + done, size - done, static_cast<off_t>(done));
      if (w <= 0) return "";
      done += static_cast<std::size_t>(w);
    }
    return "/proc/self/fd/" + std::to_string(fd_);
  }

 private:
  int fd_;
};

}  // namespace dampbound::fuzz
