#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace kautham::core {

/// Where a piece of user input came from: a file and a line in it (line 0: the whole file).
struct SourceLocation {
  std::filesystem::path file;
  int line = 0;

  std::string str() const;
};

/// Bad user input: a malformed or inconsistent problem, model or parameter.
/// The message always starts with "file:line:" so editors and terminals can jump to it.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);
  explicit InputError(const std::string& message);

  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

}  // namespace kautham::core
