#include "ChildProcess.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>

namespace kautham::apps {

namespace {

/// A file descriptor closed when it goes out of scope (the parent's copies of the child's ends).
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

int openOrThrow(const std::filesystem::path& file, int flags) {
  const int fd = ::open(file.c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), file.string());
  return fd;
}

/// In the child, between fork and exec: only async-signal-safe calls.
[[noreturn]] void becomeChild(char* const* argv, int input, int output, pid_t parent) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a parent killed outright leaves no planner behind
  if (::getppid() != parent) ::_exit(127);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  if (::dup2(input, STDIN_FILENO) < 0 || ::dup2(output, STDOUT_FILENO) < 0 ||
      ::dup2(output, STDERR_FILENO) < 0)
    ::_exit(127);
  ::execv(argv[0], argv);
  ::_exit(127);
}

}  // namespace

std::string ChildExit::describe() const {
  if (signal != 0) return fmt::format("killed by signal {} ({})", signal, ::strsignal(signal));
  return fmt::format("exit code {}", exitCode);
}

ChildProcess::ChildProcess(const std::vector<std::string>& arguments,
                           const std::filesystem::path& output) {
  if (output.has_parent_path()) std::filesystem::create_directories(output.parent_path());
  const Descriptor out(openOrThrow(output, O_WRONLY | O_CREAT | O_APPEND));
  const Descriptor in(openOrThrow("/dev/null", O_RDONLY));
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  const pid_t parent = ::getpid();
  start_ = std::chrono::steady_clock::now();
  pid_ = ::fork();
  if (pid_ < 0) throw std::system_error(errno, std::generic_category(), "fork");
  if (pid_ == 0) becomeChild(argv.data(), in.get(), out.get(), parent);
  ::setpgid(pid_, pid_);  // also here, so that kill() finds the group whoever runs first
  running_ = true;
}

ChildProcess::~ChildProcess() {
  if (running_) kill();
}

double ChildProcess::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool ChildProcess::finished() {
  if (!running_) return true;
  int status = 0;
  rusage usage{};
  pid_t ended = 0;
  do {
    ended = ::wait4(pid_, &status, WNOHANG, &usage);
  } while (ended < 0 && errno == EINTR);
  if (ended == 0) return false;
  running_ = false;
  exit_.wallTime = elapsed();
  if (ended < 0) return true;  // cannot happen for our own child; reported as exit code -1
  exit_.maxRssMb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
  if (WIFSIGNALED(status)) exit_.signal = WTERMSIG(status);
  if (WIFEXITED(status)) exit_.exitCode = WEXITSTATUS(status);
  return true;
}

void ChildProcess::kill() {
  if (!running_) return;
  ::kill(-pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  running_ = false;
  exit_.wallTime = elapsed();
  exit_.signal = SIGKILL;
}

}  // namespace kautham::apps
