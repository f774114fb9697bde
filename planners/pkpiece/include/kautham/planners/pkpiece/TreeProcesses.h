#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace kautham::planners {

/// Processes that each grow one of p-KPIECE's trees (`parallel_trees`), so that a search that
/// starts trees afresh uses every core.
///
/// Each is a fork() of the planner's process taken when its tree starts: every tree grows from
/// the same snapshot of the planner, whatever ran before it and however many processes run at
/// once (ODE's solver seed is process-wide, so threads could not do this; DESIGN.md section
/// 4). The process runs `grow(tree)`, writes the bytes that returns to its socket and exits,
/// never returning into the planner's code. One that dies without its result is an error
/// (std::runtime_error naming the tree and how it ended), never a hang. The destructor kills
/// and reaps every process still running.
///
/// A core no tree grows on can be lent to a tree still growing (lendIdleCores): the tree's
/// process learns of it through LentCores and may spread its own work over it.
class TreeProcesses {
 public:
  /// In a tree's process: the cores the search lent it.
  class LentCores {
   public:
    explicit LentCores(int fd) : fd_(fd) {}
    /// The cores lent since the last call (0 if none); never waits.
    unsigned collect();

   private:
    int fd_;
  };
  using Grow = std::function<std::vector<unsigned char>(std::size_t tree, LentCores& lent)>;
  struct Finished {
    std::size_t tree = 0;
    std::vector<unsigned char> result;  ///< what grow(tree) returned
  };

  /// At most `processes` (at least one) trees grow at once.
  TreeProcesses(unsigned processes, Grow grow);
  ~TreeProcesses();
  TreeProcesses(const TreeProcesses&) = delete;
  TreeProcesses& operator=(const TreeProcesses&) = delete;

  bool full() const { return running_.size() >= processes_; }
  bool idle() const { return running_.empty(); }
  /// Forks the process that grows `tree` (call only when not full()).
  void start(std::size_t tree);
  /// The next tree to finish, waiting at most `timeout`; nothing if none finished by then.
  std::optional<Finished> wait(std::chrono::milliseconds timeout);
  /// Kills every tree still growing: their results are not wanted.
  void stopAll() noexcept;
  /// Kills the trees growing after `tree` (whose results are not wanted once it ended the
  /// search), so that their cores can be lent.
  void stopAfter(std::size_t tree) noexcept;
  /// Lends each core that neither a tree nor a core lent before is busy on to the trees still
  /// growing, one at a time in index order from the fewest lent. Call it only once no tree is
  /// to start: a lent core stays lent until its tree ends.
  void lendIdleCores();

 private:
  struct Running {
    std::size_t tree = 0;
    pid_t pid = -1;
    int fd = -1;  ///< this process's end of the tree's socket
    std::vector<unsigned char> bytes;
    unsigned lent = 0;  ///< cores lent to the tree
  };

  [[noreturn]] void serve(std::size_t tree, int fd);
  /// Reads what is there from running_[i]; its result once the process closed its socket.
  std::optional<Finished> read(std::size_t i);
  Finished reap(std::size_t i);
  void kill(const Running& r) noexcept;

  unsigned processes_;
  Grow grow_;
  std::vector<Running> running_;
};

}  // namespace kautham::planners
