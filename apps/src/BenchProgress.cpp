#include "BenchProgress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace kautham::apps {

BenchProgress::BenchProgress(std::size_t total, std::size_t alreadyDone)
    : enabled_(isatty(STDERR_FILENO) != 0),
      total_(total),
      alreadyDone_(alreadyDone),
      start_(std::chrono::steady_clock::now()) {}

std::string BenchProgress::clock(double seconds) {
  const long whole = std::lround(std::max(seconds, 0.0));
  if (whole >= 3600)
    return fmt::format("{}:{:02}:{:02}", whole / 3600, whole / 60 % 60, whole % 60);
  return fmt::format("{}:{:02}", whole / 60, whole % 60);
}

void BenchProgress::show(std::size_t done, std::size_t solved, std::size_t failed) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done == shownDone_ && now - shown_ < std::chrono::milliseconds(500)) return;  // no flicker
  shown_ = now;
  shownDone_ = done;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // Only runs made now tell how fast this machine goes; resumed ones took no time here.
  const std::size_t madeNow = done - alreadyDone_;
  const std::string eta =
      madeNow == 0 ? "?" : clock(elapsed / static_cast<double>(madeNow) * (total_ - done));
  fmt::print(stderr, "\r  bench {:>5}/{} runs  {} solved  {} failed  elapsed {}  ETA {} ", done,
             total_, solved, failed, clock(elapsed), eta);
  std::fflush(stderr);
}

void BenchProgress::clear() {
  if (enabled_) fmt::print(stderr, "\r{:90}\r", "");
}

}  // namespace kautham::apps
