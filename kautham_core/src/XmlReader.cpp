#include "XmlReader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "kautham/core/Parameter.h"

namespace kautham::core {

namespace {

/// The element tinyxml2 names in its error text ("... XMLElement name=Robot"), if any.
std::string elementNamed(const tinyxml2::XMLDocument& document) {
  const char* text = document.ErrorStr();
  const char* name = text ? std::strstr(text, "name=") : nullptr;
  return name ? std::string(name + 5) : std::string();
}

/// tinyxml2's error, in the words of someone who wrote the file rather than of the parser.
std::string syntaxError(const tinyxml2::XMLDocument& document) {
  const std::string name = elementNamed(document);
  const std::string in = name.empty() ? "" : " in <" + name + ">";
  switch (document.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "<" + name + "> is not closed: the next end tag belongs to another element; add </" +
             name + "> where it ends (or write <" + name + " .../> if it holds nothing)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "a broken attribute" + in +
             ": write each attribute once, as name=\"value\" with the quotes";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "a broken tag" + in +
             ": a '<' must start a tag <name ...> closed by '>' (write "
             "&lt; for a '<' in text)";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "text where a tag was expected (all content goes inside the root element)";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "a comment <!-- is not closed with -->";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "a <![CDATA[ section is not closed with ]]>";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "the declaration <?xml ...?> is not closed with ?>";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "a <!...> construct is not closed with '>'";
    case tinyxml2::XML_ERROR_FILE_NOT_FOUND:
    case tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED:
    case tinyxml2::XML_ERROR_FILE_READ_ERROR:
      return "the file cannot be read (check its permissions)";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return "the elements are nested too deeply";
    default:
      return "the file is not well-formed XML";
  }
}

/// Where the file goes on after the root element's end tag with something other than white
/// space and comments (tinyxml2 accepts a second root element, and ignores a stray end tag, so
/// what follows would be dropped without a word): its offset in `text`, if anywhere. The root's
/// end tag is the first outside a comment: the roots read here (<Problem>, <robot>) do not nest.
std::optional<std::size_t> contentAfterRoot(const std::string& text, const std::string& root) {
  const std::string endTag = "</" + root;
  std::size_t at = 0;
  bool closed = false;
  while (at < text.size()) {
    if (text.compare(at, 4, "<!--") == 0) {
      const std::size_t close = text.find("-->", at + 4);
      if (close == std::string::npos) return std::nullopt;  // tinyxml2 reports it
      at = close + 3;
    } else if (closed) {
      if (!std::isspace(static_cast<unsigned char>(text[at]))) return at;
      ++at;
    } else if (text.compare(at, endTag.size(), endTag) == 0 &&
               (at + endTag.size() == text.size() || text[at + endTag.size()] == '>' ||
                std::isspace(static_cast<unsigned char>(text[at + endTag.size()])))) {
      at = text.find('>', at);
      if (at == std::string::npos) return std::nullopt;
      ++at;
      closed = true;
    } else {
      ++at;
    }
  }
  return std::nullopt;
}

}  // namespace

XmlReader::XmlReader(std::filesystem::path file) : file_(std::move(file)) {
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(file_, ignored))
    throw InputError({file_, 0}, "cannot read the file: it does not exist or is not a file");
  // The text is kept: root() looks at what follows the root element, which tinyxml2 skips.
  std::ifstream in(file_, std::ios::binary);
  if (!in) throw InputError({file_, 0}, "cannot read the file (check its permissions)");
  text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  // tinyxml2 stops at a NUL byte, and calls what came before it the document: a binary file
  // would be "empty". No UTF-8 text holds one (UTF-16 does, and tinyxml2 does not read it).
  const std::size_t nul = text_.find('\0');
  if (nul != std::string::npos)
    throw InputError(
        {file_, 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + nul, '\n'))},
        "not a text file (it holds a NUL byte, at byte " + std::to_string(nul) +
            "): expected an XML document in UTF-8 (a UTF-16 file holds NUL bytes too: save it "
            "as UTF-8)");
  const tinyxml2::XMLError status = document_.Parse(text_.data(), text_.size());
  if (status == tinyxml2::XML_ERROR_EMPTY_DOCUMENT)
    throw InputError({file_, 1}, "the file is empty: expected an XML document");
  if (status != tinyxml2::XML_SUCCESS)
    throw InputError({file_, document_.ErrorLineNum()}, "malformed XML: " + syntaxError(document_));
}

const tinyxml2::XMLElement& XmlReader::root(const char* expectedName) const {
  const tinyxml2::XMLElement* element = document_.RootElement();
  if (!element) throw InputError({file_, 1}, std::string("expected a <") + expectedName + "> root");
  if (std::strcmp(element->Name(), expectedName) != 0)
    fail(*element, std::string("expected the root element <") + expectedName + ">, found <" +
                       element->Name() + ">");
  requireNothingAfterRoot(expectedName);
  return *element;
}

void XmlReader::requireNothingAfterRoot(const char* rootName) const {
  const std::optional<std::size_t> after = contentAfterRoot(text_, rootName);
  if (!after) return;
  const int line = 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + *after, '\n'));
  std::string what = text_.substr(*after, 40);
  what = what.substr(0, what.find('\n'));
  throw InputError({file_, line}, std::string("the file goes on after </") + rootName + "> with '" +
                                      what + "': a file holds one <" + rootName +
                                      ">; remove what follows, or move it inside");
}

SourceLocation XmlReader::at(const tinyxml2::XMLElement& element) const {
  return {file_, element.GetLineNum()};
}

void XmlReader::fail(const tinyxml2::XMLElement& element, const std::string& message) const {
  throw InputError(at(element), message);
}

void XmlReader::allowAttributes(const tinyxml2::XMLElement& element,
                                std::initializer_list<const char*> allowed) const {
  for (const tinyxml2::XMLAttribute* a = element.FirstAttribute(); a; a = a->Next()) {
    bool known = false;
    for (const char* name : allowed) known = known || std::strcmp(a->Name(), name) == 0;
    if (known) continue;
    std::string list;
    for (const char* name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
    fail(element, std::string("<") + element.Name() + "> has no attribute '" + a->Name() +
                      "'; allowed: " + (list.empty() ? "none" : list));
  }
}

void XmlReader::atMostOnce(const tinyxml2::XMLElement& element,
                           std::initializer_list<const char*> tags) const {
  for (const char* tag : tags) {
    const tinyxml2::XMLElement* first = element.FirstChildElement(tag);
    if (const tinyxml2::XMLElement* second = first ? first->NextSiblingElement(tag) : nullptr)
      fail(*second, std::string("<") + tag + "> appears twice inside <" + element.Name() +
                        "> (first on line " + std::to_string(first->GetLineNum()) + "); keep one");
  }
}

void XmlReader::allowChildren(const tinyxml2::XMLElement& element,
                              std::initializer_list<const char*> allowed) const {
  for (const tinyxml2::XMLElement* c = element.FirstChildElement(); c;
       c = c->NextSiblingElement()) {
    bool known = false;
    for (const char* name : allowed) known = known || std::strcmp(c->Name(), name) == 0;
    if (known) continue;
    std::string list;
    for (const char* name : allowed) list += (list.empty() ? "<" : ", <") + std::string(name) + ">";
    fail(*c, std::string("unexpected <") + c->Name() + "> inside <" + element.Name() +
                 ">; expected " + list);
  }
}

std::optional<std::string> XmlReader::optionalText(const tinyxml2::XMLElement& element,
                                                   const char* attribute) const {
  const char* value = element.Attribute(attribute);
  return value ? std::optional<std::string>(value) : std::nullopt;
}

std::string XmlReader::requiredText(const tinyxml2::XMLElement& element,
                                    const char* attribute) const {
  auto value = optionalText(element, attribute);
  if (!value || value->empty())
    fail(element, std::string("<") + element.Name() + "> needs the attribute " + attribute);
  return *value;
}

double XmlReader::number(const tinyxml2::XMLElement& element, const char* attribute,
                         double fallback) const {
  auto text = optionalText(element, attribute);
  if (!text) return fallback;
  auto values = parseNumbers(element, *text, std::string("attribute ") + attribute);
  if (values.size() != 1)
    fail(element,
         std::string("attribute ") + attribute + " must be one number, got '" + *text + "'");
  return values.front();
}

double XmlReader::requiredNumber(const tinyxml2::XMLElement& element, const char* attribute) const {
  requiredText(element, attribute);
  return number(element, attribute, 0.0);
}

int XmlReader::integer(const tinyxml2::XMLElement& element, const char* attribute,
                       int fallback) const {
  const double value = number(element, attribute, fallback);
  if (value != std::floor(value) || std::abs(value) > 1e9)
    fail(element, std::string("attribute ") + attribute + " must be a whole number");
  return static_cast<int>(value);
}

bool XmlReader::flag(const tinyxml2::XMLElement& element, const char* attribute,
                     bool fallback) const {
  const auto text = optionalText(element, attribute);
  if (!text) return fallback;
  if (const std::optional<bool> flag = flagWord(*text)) return *flag;
  fail(element,
       std::string("attribute ") + attribute + " must be true or false, got '" + *text + "'");
}

Eigen::Vector3d XmlReader::vector3(const tinyxml2::XMLElement& element, const char* attribute,
                                   const Eigen::Vector3d& fallback) const {
  auto text = optionalText(element, attribute);
  if (!text) return fallback;
  auto values = parseNumbers(element, *text, std::string("attribute ") + attribute);
  if (values.size() != 3)
    fail(element, std::string("attribute ") + attribute +
                      " must be three numbers \"x y z\", got '" + *text + "'");
  return {values[0], values[1], values[2]};
}

std::string XmlReader::elementText(const tinyxml2::XMLElement& element) const {
  const char* text = element.GetText();
  std::string value = text ? text : "";
  const auto first = value.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return value.substr(first, value.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<double> XmlReader::numbersInAttribute(const tinyxml2::XMLElement& element,
                                                  const char* attribute) const {
  return parseNumbers(element, requiredText(element, attribute),
                      std::string("attribute ") + attribute);
}

std::vector<double> XmlReader::numbersInText(const tinyxml2::XMLElement& element) const {
  return parseNumbers(element, elementText(element), std::string("<") + element.Name() + ">");
}

std::vector<double> XmlReader::parseNumbers(const tinyxml2::XMLElement& element,
                                            const std::string& text,
                                            const std::string& what) const {
  std::vector<double> values;
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0')
      fail(element, what + ": expected a number, got '" + word + "'");
    if (beyondDouble(word))
      fail(element, what + ": " + word +
                        " is out of range: beyond the largest number a double holds (about "
                        "1.8e308)");
    if (!std::isfinite(value))
      fail(element, what + ": expected a finite number, got '" + word + "'");
    values.push_back(value);
  }
  return values;
}

}  // namespace kautham::core
