#include "JsonFileText.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "kautham/core/InputError.h"

namespace kautham::apps {

nlohmann::json JsonFileText::parse(const std::string& kind, const std::string& notJson) {
  std::error_code ignored;
  if (std::filesystem::is_directory(file_, ignored))
    throw core::InputError({file_, 0}, "a folder, not a file: name " + kind + " itself");
  std::ifstream in(file_, std::ios::binary);
  if (!in) throw core::InputError({file_, 0}, "cannot open " + kind);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text_ = buffer.str();
  try {
    return nlohmann::json::parse(text_);
  } catch (const nlohmann::json::parse_error& e) {
    throw core::InputError({file_, lineAt(e.byte == 0 ? 0 : e.byte - 1)}, notJson + e.what());
  }
}

int JsonFileText::lineAt(std::size_t offset) const {
  offset = std::min(offset, text_.size());
  return 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + offset, '\n'));
}

std::size_t JsonFileText::keyOffset(const std::string& key) const {
  return text_.find("\"" + key + "\"");
}

int JsonFileText::keyLine(const std::string& key) const {
  const std::size_t at = keyOffset(key);
  return at == std::string::npos ? 0 : lineAt(at);
}

namespace {

bool isJsonSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// The offset just past the string that opens at `at` (a '"'), escapes skipped.
std::size_t pastString(const std::string& text, std::size_t at) {
  for (++at; at < text.size(); ++at) {
    if (text[at] == '\\')
      ++at;
    else if (text[at] == '"')
      return at + 1;
  }
  return text.size();
}

/// The offset of element `index` of the array opening at `open` (a '['); npos when it has
/// fewer. The text parsed as JSON, so only strings and nesting need care.
std::size_t arrayElement(const std::string& text, std::size_t open, std::size_t index) {
  std::size_t element = 0;
  int depth = 0;
  bool expectElement = true;  // after '[' or a top-level ',': the next value starts one
  for (std::size_t at = open; at < text.size();) {
    const char c = text[at];
    if (depth == 1 && expectElement && !isJsonSpace(c) && c != ']') {
      if (element == index) return at;
      expectElement = false;
    }
    if (c == '"') {
      at = pastString(text, at);
      continue;
    }
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') {
      if (--depth == 0) return std::string::npos;
    }
    if (c == ',' && depth == 1) {
      ++element;
      expectElement = true;
    }
    ++at;
  }
  return std::string::npos;
}

}  // namespace

int JsonFileText::elementLine(const std::string& key, std::size_t index) const {
  const std::size_t at = keyOffset(key);
  if (at == std::string::npos) return 0;
  std::size_t open = at + key.size() + 2;
  while (open < text_.size() && (isJsonSpace(text_[open]) || text_[open] == ':')) ++open;
  if (open >= text_.size() || text_[open] != '[') return lineAt(at);
  const std::size_t element = arrayElement(text_, open, index);
  return lineAt(element == std::string::npos ? at : element);
}

}  // namespace kautham::apps
