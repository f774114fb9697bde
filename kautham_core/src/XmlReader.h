#pragma once

// Private helper of the loaders: reads a tinyxml2 document and turns every problem into an
// InputError that names the file, the line and what was expected.

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <tinyxml2.h>
#include <Eigen/Core>

#include "kautham/core/InputError.h"

namespace kautham::core {

class XmlReader {
 public:
  /// Loads and parses the file; XML syntax errors become InputError with the line.
  explicit XmlReader(std::filesystem::path file);

  /// The root element, which must be named `expectedName`.
  const tinyxml2::XMLElement& root(const char* expectedName) const;
  /// The root element whatever its name (nullptr for none), to tell one kind of file from another.
  const tinyxml2::XMLElement* anyRoot() const { return document_.RootElement(); }

  SourceLocation at(const tinyxml2::XMLElement& element) const;
  [[noreturn]] void fail(const tinyxml2::XMLElement& element, const std::string& message) const;

  /// Rejects attributes other than `allowed` (catches typos such as maxTilts="...").
  void allowAttributes(const tinyxml2::XMLElement& element,
                       std::initializer_list<const char*> allowed) const;
  /// Rejects a second child named like one of `tags` (a second <Home> would silently win).
  void atMostOnce(const tinyxml2::XMLElement& element,
                  std::initializer_list<const char*> tags) const;
  /// Rejects child elements other than `allowed` (catches typos such as <Paramter>).
  void allowChildren(const tinyxml2::XMLElement& element,
                     std::initializer_list<const char*> allowed) const;

  std::optional<std::string> optionalText(const tinyxml2::XMLElement& element,
                                          const char* attribute) const;
  std::string requiredText(const tinyxml2::XMLElement& element, const char* attribute) const;
  double number(const tinyxml2::XMLElement& element, const char* attribute, double fallback) const;
  double requiredNumber(const tinyxml2::XMLElement& element, const char* attribute) const;
  int integer(const tinyxml2::XMLElement& element, const char* attribute, int fallback) const;
  /// A yes/no attribute, read as planner flags are (core::flagWord: true, yes, on, 1, ...).
  bool flag(const tinyxml2::XMLElement& element, const char* attribute, bool fallback) const;
  /// Three numbers in one attribute, "x y z".
  Eigen::Vector3d vector3(const tinyxml2::XMLElement& element, const char* attribute,
                          const Eigen::Vector3d& fallback) const;
  /// The whitespace-separated numbers of a required attribute, e.g. init="0.5 0.5".
  std::vector<double> numbersInAttribute(const tinyxml2::XMLElement& element,
                                         const char* attribute) const;
  /// The whitespace-separated numbers of an element's text, e.g. <Init>0.5 0.5</Init>.
  std::vector<double> numbersInText(const tinyxml2::XMLElement& element) const;
  std::string elementText(const tinyxml2::XMLElement& element) const;

  const std::filesystem::path& file() const { return file_; }

 private:
  /// Throws if the file goes on after the root element's end tag (a second root element, a
  /// stray end tag), which tinyxml2 would accept and this reader would never read.
  void requireNothingAfterRoot(const char* rootName) const;

  std::vector<double> parseNumbers(const tinyxml2::XMLElement& element, const std::string& text,
                                   const std::string& what) const;

  std::filesystem::path file_;
  std::string text_;  // the file as read, for what tinyxml2 does not report (root())
  tinyxml2::XMLDocument document_;
};

}  // namespace kautham::core
