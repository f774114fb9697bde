#include "kautham/planners/pkpiece/TreeProcesses.h"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "ProcessIo.h"

namespace kautham::planners {

using namespace process_io;

// A result is [n] (uint64) and n bytes; the process then exits with status 0. The other way,
// each byte the search writes to a tree's socket lends it one core.

unsigned TreeProcesses::LentCores::collect() {
  unsigned char bytes[64];
  ssize_t n;
  do n = ::recv(fd_, bytes, sizeof bytes, MSG_DONTWAIT);
  while (n < 0 && errno == EINTR);
  return n > 0 ? static_cast<unsigned>(n) : 0u;  // nothing there, or the search gone
}

TreeProcesses::TreeProcesses(unsigned processes, Grow grow)
    : processes_(processes == 0 ? 1 : processes), grow_(std::move(grow)) {}

TreeProcesses::~TreeProcesses() { stopAll(); }

void TreeProcesses::start(std::size_t tree) {
  const Forked forked = forkWithSocket("tree processes");
  if (forked.pid == 0) {
    for (const Running& r : running_) ::close(r.fd);  // the tree keeps only its own socket
    serve(tree, forked.fd);
  }
  running_.push_back({tree, forked.pid, forked.fd, {}});
}

void TreeProcesses::serve(std::size_t tree, int fd) {
  // Ctrl-C reaches the whole process group: the planner's process decides what it means.
  std::signal(SIGINT, SIG_IGN);
  int code = 0;
  try {
    LentCores lent(fd);
    const std::vector<unsigned char> result = grow_(tree, lent);
    const std::uint64_t size = result.size();
    if (writeAll(fd, &size, sizeof size) != Io::Ok ||
        writeAll(fd, result.data(), result.size()) != Io::Ok)
      code = 1;
  } catch (const std::exception& e) {
    // The planner's process reports the tree's death; the reason is only known here.
    std::fprintf(stderr, "p-KPIECE, tree %zu: %s\n", tree, e.what());
    code = 2;
  } catch (...) {
    code = 2;
  }
  // Never return into the planner's code, never run its destructors or atexit handlers.
  ::_exit(code);
}

std::optional<TreeProcesses::Finished> TreeProcesses::wait(std::chrono::milliseconds timeout) {
  if (running_.empty()) return std::nullopt;
  std::vector<pollfd> fds;
  for (const Running& r : running_) fds.push_back({r.fd, POLLIN, 0});
  int ready;
  do ready = ::poll(fds.data(), fds.size(), static_cast<int>(timeout.count()));
  while (ready < 0 && errno == EINTR);
  if (ready < 0) throw std::system_error(errno, std::generic_category(), "tree processes: poll");
  for (std::size_t i = 0; i < fds.size(); ++i)
    if (fds[i].revents != 0)
      if (std::optional<Finished> done = read(i)) return done;
  return std::nullopt;
}

std::optional<TreeProcesses::Finished> TreeProcesses::read(std::size_t i) {
  Running& r = running_[i];
  unsigned char chunk[1 << 16];
  ssize_t n;
  do n = ::read(r.fd, chunk, sizeof chunk);
  while (n < 0 && errno == EINTR);
  if (n > 0) {
    r.bytes.insert(r.bytes.end(), chunk, chunk + n);
    return std::nullopt;
  }
  return reap(i);  // closed (or broken): the process is done
}

TreeProcesses::Finished TreeProcesses::reap(std::size_t i) {
  const Running r = running_[i];
  running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(i));
  ::close(r.fd);
  int status = 0;
  waitFor(r.pid, &status, 0);
  std::uint64_t size = 0;
  if (r.bytes.size() >= sizeof size) std::memcpy(&size, r.bytes.data(), sizeof size);
  const bool whole = r.bytes.size() >= sizeof size && r.bytes.size() - sizeof size == size;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !whole)
    throw std::runtime_error("p-KPIECE: the process growing tree " + std::to_string(r.tree) + " " +
                             describeStatus(status) + " without its result");
  return {r.tree, std::vector<unsigned char>(r.bytes.begin() + sizeof size, r.bytes.end())};
}

void TreeProcesses::stopAll() noexcept {
  for (const Running& r : running_) kill(r);
  running_.clear();
}

void TreeProcesses::stopAfter(std::size_t tree) noexcept {
  const auto later = [tree](const Running& r) { return r.tree > tree; };
  for (const Running& r : running_)
    if (later(r)) kill(r);
  running_.erase(std::remove_if(running_.begin(), running_.end(), later), running_.end());
}

void TreeProcesses::kill(const Running& r) noexcept {
  ::kill(r.pid, SIGKILL);
  ::close(r.fd);
  int status = 0;
  waitFor(r.pid, &status, 0);
}

void TreeProcesses::lendIdleCores() {
  unsigned busy = 0;
  for (const Running& r : running_) busy += 1 + r.lent;
  while (busy < processes_ && !running_.empty()) {
    // The earliest of the trees with the fewest cores lent (running_ is in start order).
    Running* to = &running_.front();
    for (Running& r : running_)
      if (r.lent < to->lent) to = &r;
    const unsigned char core = 1;
    // A tree that has just ended reads nothing more: its core comes back when it is reaped.
    // MSG_NOSIGNAL: a closed socket is no reason to die.
    if (::send(to->fd, &core, 1, MSG_NOSIGNAL | MSG_DONTWAIT) != 1) break;
    ++to->lent;
    ++busy;
  }
}

}  // namespace kautham::planners
