#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace kautham::apps {

/// A JSON input file (a plan, a benchmark file) read whole and kept as text, so that errors
/// about it can name the line of what they are about.
class JsonFileText {
 public:
  explicit JsonFileText(std::filesystem::path file) : file_(std::move(file)) {}

  /// Reads and parses the file. Throws core::InputError: "cannot open `kind`" (line 0), or
  /// `notJson` followed by the parser's message, at the line where parsing stopped.
  nlohmann::json parse(const std::string& kind, const std::string& notJson);

  /// 1-based line of a byte offset into the text (the last line past its end).
  int lineAt(std::size_t offset) const;
  /// Line of the first "key" in the text; 0 when it is not there.
  int keyLine(const std::string& key) const;
  /// Line of element `index` of the array that the first "key" holds: where an error about
  /// `key[index]` points. The key's line when the array has fewer elements or `key` holds no
  /// array; 0 when `key` is not there.
  int elementLine(const std::string& key, std::size_t index) const;

  const std::string& text() const { return text_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  /// Offset of the first "key" in the text; npos when it is not there.
  std::size_t keyOffset(const std::string& key) const;

  std::filesystem::path file_;
  std::string text_;
};

}  // namespace kautham::apps
