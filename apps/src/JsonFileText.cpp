#include "JsonFileText.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "kautham/core/InputError.h"

namespace kautham::apps {

nlohmann::json JsonFileText::parse(const std::string& kind, const std::string& notJson) {
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

int JsonFileText::keyLine(const std::string& key) const {
  const std::size_t at = text_.find("\"" + key + "\"");
  return at == std::string::npos ? 0 : lineAt(at);
}

}  // namespace kautham::apps
