#pragma once

// The progress of `kautham bench`: on a terminal one line that keeps updating (runs done of
// all, solved and failed so far, elapsed time, an estimate of the time left); in a pipe or a
// CI log nothing, so that only the final summary shows.

#include <chrono>
#include <cstddef>
#include <string>

namespace kautham::apps {

class BenchProgress {
 public:
  /// `total` runs, of which `alreadyDone` had results before this invocation.
  BenchProgress(std::size_t total, std::size_t alreadyDone);

  void show(std::size_t done, std::size_t solved, std::size_t failed);
  /// Removes the line, before the summary is printed.
  void clear();

  /// "1:02:03" or "2:03".
  static std::string clock(double seconds);

 private:
  bool enabled_;
  std::size_t total_;
  std::size_t alreadyDone_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point shown_;
  std::size_t shownDone_ = static_cast<std::size_t>(-1);
};

}  // namespace kautham::apps
