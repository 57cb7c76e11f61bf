#include "tests/engine/problems/xml_reader.hpp"

#include <cctype>
#include <stdexcept>

namespace kinema_test {
namespace {

class XmlParser {
 public:
  explicit XmlParser(const std::string& text) : s_(text) {}

  XmlElement document() {
    if (s_.compare(0, 5, "<?xml") == 0) skip_past("?>");
    skip_misc();
    XmlElement root = element();
    skip_misc();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  const std::string& s_;
  std::size_t i_ = 0;

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("not well formed at offset " + std::to_string(i_) + ": " + what);
  }
  bool at(const char* literal) const { return s_.compare(i_, std::char_traits<char>::length(literal), literal) == 0; }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void skip_past(const char* end) {
    const auto found = s_.find(end, i_);
    if (found == std::string::npos) fail(std::string("no ") + end);
    i_ = found + std::char_traits<char>::length(end);
  }
  // Space and comments between elements.
  void skip_misc() {
    for (skip_space(); at("<!--"); skip_space()) skip_past("-->");
  }
  std::string name() {
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_' || s_[i_] == '-' ||
                              s_[i_] == ':' || s_[i_] == '.'))
      ++i_;
    if (i_ == start) fail("a name expected");
    return s_.substr(start, i_ - start);
  }
  // An entity or character reference after '&'.
  std::string reference() {
    const auto end = s_.find(';', i_);
    if (end == std::string::npos || end - i_ > 10) fail("& that starts no reference");
    const std::string ref = s_.substr(i_ + 1, end - i_ - 1);
    i_ = end + 1;
    if (ref == "amp") return "&";
    if (ref == "lt") return "<";
    if (ref == "gt") return ">";
    if (ref == "quot") return "\"";
    if (ref == "apos") return "'";
    if (ref.size() > 1 && ref[0] == '#') {
      const unsigned long code = ref[1] == 'x' ? std::stoul(ref.substr(2), nullptr, 16) : std::stoul(ref.substr(1));
      if (code < 128) return std::string(1, static_cast<char>(code));
      return "?";  // the tests' documents are ASCII
    }
    fail("unknown entity &" + ref + ";");
  }
  std::string attribute_value() {
    const char quote = i_ < s_.size() ? s_[i_] : 0;
    if (quote != '"' && quote != '\'') fail("an attribute value must be quoted");
    ++i_;
    std::string value;
    while (i_ < s_.size() && s_[i_] != quote) {
      if (s_[i_] == '<') fail("< in an attribute value");
      if (s_[i_] == '&') value += reference();
      else value += s_[i_++];
    }
    if (i_ >= s_.size()) fail("an attribute value not closed");
    ++i_;
    return value;
  }
  XmlElement element() {
    if (!at("<")) fail("an element expected");
    ++i_;
    XmlElement e;
    e.name = name();
    for (;;) {
      skip_space();
      if (at("/>")) {
        i_ += 2;
        return e;
      }
      if (at(">")) break;
      const std::string key = name();
      skip_space();
      if (!at("=")) fail("= expected after attribute " + key);
      ++i_;
      skip_space();
      if (!e.attributes.emplace(key, attribute_value()).second) fail("attribute " + key + " twice");
    }
    ++i_;
    while (!at("</")) {
      if (i_ >= s_.size()) fail("<" + e.name + "> not closed");
      if (at("<!--")) skip_past("-->");
      else if (at("<![CDATA[")) {
        const auto end = s_.find("]]>", i_);
        if (end == std::string::npos) fail("CDATA not closed");
        e.text += s_.substr(i_ + 9, end - i_ - 9);
        i_ = end + 3;
      } else if (at("<")) e.children.push_back(element());
      else if (at("&")) e.text += reference();
      else e.text += s_[i_++];
    }
    i_ += 2;
    if (name() != e.name) fail("</...> does not close <" + e.name + ">");
    skip_space();
    if (!at(">")) fail("> expected");
    ++i_;
    return e;
  }
};

}  // namespace

const XmlElement& XmlElement::child(const std::string& child_name) const {
  for (const XmlElement& c : children)
    if (c.name == child_name) return c;
  throw std::runtime_error("<" + name + "> has no <" + child_name + ">");
}

XmlElement parse_xml(const std::string& text) { return XmlParser(text).document(); }

}  // namespace kinema_test
