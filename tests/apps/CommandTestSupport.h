#pragma once

// Running the `kautham` program from tests, as a user would from the repository's root.

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace kautham::test {

struct CommandRun {
  int exitCode = -1;
  std::string output;  ///< what the command printed (stdout, plus stderr when redirected)
};

/// Runs a shell command and collects its output and exit code.
inline CommandRun run(const std::string& command) {
  CommandRun result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// `kautham ARGUMENTS` in the repository's root, stdout and stderr together.
inline CommandRun kautham(const std::string& arguments) {
  return run("cd '" + std::string(KAUTHAM_SOURCE_DIR) + "' && '" + KAUTHAM_BINARY + "' " +
             arguments + " 2>&1");
}

inline std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void writeFile(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

/// A test with a fresh temporary folder of its own, removed afterwards.
class TemporaryFolderTest : public ::testing::Test {
 protected:
  std::filesystem::path folder =
      std::filesystem::temp_directory_path() /
      ("kautham_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { std::filesystem::create_directories(folder); }
  void TearDown() override { std::filesystem::remove_all(folder); }
};

}  // namespace kautham::test
