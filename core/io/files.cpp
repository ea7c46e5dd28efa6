#include "core/io/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <sstream>
#include <streambuf>
#include <vector>

#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

std::string errno_text(int err) { return std::strerror(err); }

/// Where an output for PATH goes: PATH itself, or the file a symbolic link names (a user who
/// links out.csv elsewhere expects the file there to change, not the link to be replaced).
/// Refuses what is not, or cannot become, a regular file.
std::string output_target(const std::string& path) {
  if (path.empty()) throw InputError("an output path is empty");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno != ENOENT) throw InputError(path + ": " + errno_text(errno));
    struct stat lst {};
    if (::lstat(path.c_str(), &lst) == 0)  // a dangling link: refuse rather than guess
      throw InputError(path + ": is a symbolic link to a missing file");
    return path;
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a directory, not a file");
  if (!S_ISREG(st.st_mode))
    throw InputError(path +
                     ": is not a regular file (a device, FIFO or socket); dampbound writes only "
                     "regular files");
  char buf[PATH_MAX];
  struct stat lst {};
  if (::lstat(path.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode) && ::realpath(path.c_str(), buf))
    return buf;
  return path;
}

/// An ostream buffer over a file descriptor that remembers the first failed write.
class FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, const std::string& path) : fd_(fd), path_(path), buf_(1 << 16) {
    setp(buf_.data(), buf_.data() + buf_.size());
  }
  int sync() override {
    const std::string_view pending(pbase(), static_cast<size_t>(pptr() - pbase()));
    setp(buf_.data(), buf_.data() + buf_.size());
    write_all(fd_, pending, path_);
    return 0;
  }
  int_type overflow(int_type c) override {
    if (sync() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }

 private:
  int fd_;
  const std::string& path_;
  std::vector<char> buf_;
};

}  // namespace

void sync_directory(const std::string& path) {
  const int fd = ::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void write_all(int fd, std::string_view bytes, const std::string& path) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw InputError(path + ": write failed: " + errno_text(w < 0 ? errno : ENOSPC));
    done += static_cast<size_t>(w);
  }
}

PendingOutput::PendingOutput(const std::string& path, const std::function<void(int fd)>& fill)
    : path_(output_target(path)) {
  const std::string dir = directory_of(path_);
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError(path + ": the directory does not exist or is not writable");
  fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (fd_ < 0) {  // no O_TMPFILE on this file system: a named temporary, removed on failure
    tmp_ = path_ + ".tmp." + std::to_string(::getpid());
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError(path + ": cannot write the file (" + errno_text(errno) + ")");
  }
  try {
    fill(fd_);
    if (::fsync(fd_) != 0)
      throw InputError(path + ": write failed: " + errno_text(errno));
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    if (!tmp_.empty()) ::unlink(tmp_.c_str());
    throw;
  }
}

PendingOutput::~PendingOutput() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void PendingOutput::commit() {
  if (fd_ < 0) throw InputError(path_ + ": the output was already written");
  if (tmp_.empty()) {
    // Give the anonymous file a name beside PATH, then rename it over PATH: rename replaces
    // an existing file atomically, linkat cannot.
    tmp_ = path_ + ".tmp." + std::to_string(::getpid());
    const std::string self = "/proc/self/fd/" + std::to_string(fd_);
    ::unlink(tmp_.c_str());
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, tmp_.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      const int err = errno;
      tmp_.clear();
      throw InputError(path_ + ": cannot create the file (" + errno_text(err) + ")");
    }
  }
  const bool closed = ::close(fd_) == 0;
  fd_ = -1;
  if (!closed || std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    tmp_.clear();
    throw InputError(path_ + ": cannot move the finished file into place (" + errno_text(err) +
                     ")");
  }
  tmp_.clear();
  sync_directory(path_);
}

void write_stream(int fd, const std::string& path,
                  const std::function<void(std::ostream&)>& write) {
  FdBuf buf(fd, path);
  std::ostream out(&buf);
  out.exceptions(std::ios::badbit);  // a failed write (InputError) reaches the caller
  try {
    write(out);
    out.flush();
  } catch (const std::ios::failure&) {
  }
  if (buf.pubsync() != 0 || !out) throw InputError(path + ": write failed");
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  PendingOutput(path, [&](int fd) { write_stream(fd, path, write); }).commit();
}

void write_durably(const std::string& path, const std::function<void(std::FILE*)>& fill) {
  PendingOutput(path, [&](int fd) {
    const int own = ::dup(fd);
    std::FILE* f = own >= 0 ? ::fdopen(own, "wb") : nullptr;
    if (!f) {
      if (own >= 0) ::close(own);
      throw InputError(path + ": cannot write the file (" + errno_text(errno) + ")");
    }
    static thread_local std::vector<char> buffer(1 << 20);
    std::setvbuf(f, buffer.data(), _IOFBF, buffer.size());
    try {
      fill(f);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    bool ok = std::fflush(f) == 0 && !std::ferror(f);
    const int err = errno;
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw InputError(path + ": write failed: " + errno_text(err ? err : ENOSPC));
  }).commit();
}

void write_file_bytes(const std::string& path, std::string_view bytes) {
  PendingOutput(path, [&](int fd) { write_all(fd, bytes, path); }).commit();
}

void check_writable(const std::string& path) {
  const std::string target = output_target(path);
  if (::access(directory_of(target).c_str(), W_OK) != 0)
    throw InputError(path + ": the directory does not exist or is not writable");
}

void check_regular_input(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(path + ": cannot open the file (" + errno_text(errno) + ")");
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a directory, not a file");
  if (!S_ISREG(st.st_mode))
    throw InputError(path + ": is not a regular file (a device, FIFO or socket)");
}

std::string read_file_text(const std::string& path, std::uint64_t max_bytes) {
  check_regular_input(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(path + ": cannot open the file (" + errno_text(errno) + ")");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {  // replaced since check_regular_input
    ::close(fd);
    throw InputError(path + ": is not a regular file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputError(path + ": the file is " + std::to_string(st.st_size) + " bytes, more than " +
                     "the limit of " + std::to_string(max_bytes) + " bytes for this kind of file");
  }
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw InputError(path + ": cannot read the file (" + errno_text(err) + ")");
    }
    if (n == 0) break;
    text.append(buf, static_cast<size_t>(n));
    if (text.size() > max_bytes) {  // it grew while being read
      ::close(fd);
      throw InputError(path + ": the file is larger than the limit of " +
                       std::to_string(max_bytes) + " bytes for this kind of file");
    }
  }
  ::close(fd);
  return text;
}


}  // namespace dampbound
