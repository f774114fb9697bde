#pragma once

// Bytes between the planner's process and the processes it forks (ParticleWorkers,
// TreeProcesses): raw values packed in order, and reads and writes that finish or say why not.

#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace kautham::planners::process_io {

/// Appends raw bytes; Unpacker reads them back in order.
class Packer {
 public:
  explicit Packer(std::vector<unsigned char>& buffer) : buffer_(buffer) { buffer_.clear(); }
  void put(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    buffer_.insert(buffer_.end(), bytes, bytes + size);
  }
  void put(std::uint64_t value) { put(&value, sizeof value); }
  void put(double value) { put(&value, sizeof value); }
  void put(const std::vector<double>& values) {
    put(std::uint64_t{values.size()});
    put(values.data(), values.size() * sizeof(double));
  }

 private:
  std::vector<unsigned char>& buffer_;
};

/// Reads what a Packer wrote. A read past the end throws: a message shorter than it announces
/// is corrupt.
class Unpacker {
 public:
  explicit Unpacker(const std::vector<unsigned char>& buffer)
      : data_(buffer.data()), size_(buffer.size()) {}
  void get(void* data, std::size_t size) {
    if (size > size_ - offset_) throw std::runtime_error("a message from a process is truncated");
    std::memcpy(data, data_ + offset_, size);
    offset_ += size;
  }
  std::uint64_t u64() {
    std::uint64_t value = 0;
    get(&value, sizeof value);
    return value;
  }
  double real() {
    double value = 0.0;
    get(&value, sizeof value);
    return value;
  }
  /// A vector put by Packer::put(const std::vector<double>&), of at most `limit` values.
  std::vector<double> reals(std::size_t limit) {
    const std::uint64_t size = u64();
    if (size > limit) throw std::runtime_error("a message from a process is corrupt");
    std::vector<double> values(size);
    get(values.data(), size * sizeof(double));
    return values;
  }

 private:
  const unsigned char* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

enum class Io { Ok, Closed, Failed };

/// Reads exactly `size` bytes (retrying partial reads and EINTR). Closed: end of file.
inline Io readAll(int fd, void* data, std::size_t size) {
  auto* bytes = static_cast<unsigned char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno == ECONNRESET ? Io::Closed : Io::Failed;
    if (n == 0) return Io::Closed;
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
  return Io::Ok;
}

/// Writes exactly `size` bytes to a socket; a closed peer is an error, not SIGPIPE.
inline Io writeAll(int fd, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, bytes, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno == EPIPE || errno == ECONNRESET ? Io::Closed : Io::Failed;
    bytes += n;
    size -= static_cast<std::size_t>(n);
  }
  return Io::Ok;
}

/// A process forked with a socket to it: `fd` is this process's end of the socket, the child's
/// in the child (pid 0), the parent's in the parent; the other end is closed on each side, so
/// the socket closes when either process goes away.
struct Forked {
  pid_t pid = -1;
  int fd = -1;
};

/// socketpair() and fork(); throws std::system_error naming `who` when either fails.
inline Forked forkWithSocket(const std::string& who) {
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw std::system_error(errno, std::generic_category(), who + ": socketpair");
  // Text this process has buffered would otherwise be written again by the child.
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  // A child outlives no parent: killed alone (SIGTERM, SIGKILL), the planner takes its
  // processes with it.
  if (pid == 0 && (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent)) ::_exit(3);
  if (pid < 0) {
    const int error = errno;
    ::close(ends[0]);
    ::close(ends[1]);
    throw std::system_error(error, std::generic_category(), who + ": fork");
  }
  ::close(ends[pid == 0 ? 0 : 1]);
  return {pid, ends[pid == 0 ? 1 : 0]};
}

inline pid_t waitFor(pid_t pid, int* status, int options) {
  pid_t r;
  do r = ::waitpid(pid, status, options);
  while (r < 0 && errno == EINTR);
  return r;
}

/// How a child process ended, for an error message.
inline std::string describeStatus(int status) {
  if (WIFSIGNALED(status))
    return "killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
           ::strsignal(WTERMSIG(status)) + ")";
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  return "stopped (status " + std::to_string(status) + ")";
}

}  // namespace kautham::planners::process_io
