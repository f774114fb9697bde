#include "kautham/core/InputError.h"

namespace kautham::core {

std::string SourceLocation::str() const {
  if (file.empty()) return "<input>";
  return line > 0 ? file.string() + ":" + std::to_string(line) : file.string();
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.str() + ": " + message), where_(std::move(where)) {}

InputError::InputError(const std::string& message) : std::runtime_error(message) {}

}  // namespace kautham::core
