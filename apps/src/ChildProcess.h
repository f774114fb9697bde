#pragma once

// A child process that runs a command with its output appended to a file. Each child leads a
// process group of its own: Ctrl-C on the terminal reaches only the parent, which decides what
// to stop, and killing the group also ends the child's own workers (p-KPIECE's particles).

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace kautham::apps {

/// How a child ended.
struct ChildExit {
  int exitCode = -1;      ///< -1 when a signal ended it
  int signal = 0;         ///< the signal that ended it, 0 if it exited
  double wallTime = 0.0;  ///< seconds from start to end
  double maxRssMb = 0.0;  ///< peak resident memory of the child (or its largest waited-for child)

  bool exited(int code) const { return signal == 0 && exitCode == code; }
  std::string describe() const;  ///< "exit code 2", "killed by signal 11 (Segmentation fault)"
};

class ChildProcess {
 public:
  /// Starts `arguments` (the program first), stdin from /dev/null, stdout and stderr appended to
  /// `output`. Throws std::runtime_error if the child cannot be made.
  ChildProcess(const std::vector<std::string>& arguments, const std::filesystem::path& output);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  ///< kills a child still running: none outlives its owner

  /// True once the child has ended (then exit() tells how); never blocks.
  bool finished();
  const ChildExit& exit() const { return exit_; }
  double elapsed() const;
  /// Kills the child's whole process group and waits for the child.
  void kill();

 private:
  pid_t pid_ = -1;
  bool running_ = false;
  std::chrono::steady_clock::time_point start_;
  ChildExit exit_;
};

}  // namespace kautham::apps
