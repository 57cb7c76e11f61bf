// A small XML reader for the tests: enough of XML 1.0 to tell a document well formed
// (one root, every tag closed in order, attributes quoted, & only in the five named
// entities or a character reference, nothing after the root) and read it back as a tree.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace kinema_test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  ///< The character data directly inside, entities decoded.
  std::vector<XmlElement> children;
  /// The first child of that name; std::runtime_error if none.
  const XmlElement& child(const std::string& child_name) const;
};

/// The document's root element; std::runtime_error naming the offset where it is not well formed.
XmlElement parse_xml(const std::string& text);

}  // namespace kinema_test
