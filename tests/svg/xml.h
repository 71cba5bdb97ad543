// A strict reader of the XML the SVG writers write, for tests: it accepts
// well-formed XML 1.0 documents made of one root element, nested elements
// with quoted attributes, character data, the five predefined entities and
// numeric character references, comments, and a leading declaration; and
// it rejects everything else it sees (mismatched or unclosed tags, an
// attribute given twice or unquoted, a bare '<' or '&', text outside the
// root). Not a general XML parser: no DTDs, CDATA or processing
// instructions besides the declaration.
#ifndef ANIMAT_TESTS_SVG_XML_H_
#define ANIMAT_TESTS_SVG_XML_H_

#include <cctype>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace animat::testing {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;  // Entities decoded.
  std::vector<XmlElement> children;
  std::string text;  // Character data directly inside, entities decoded.

  // The attribute's value, or "" when absent.
  std::string Attribute(const std::string& key) const {
    auto it = attributes.find(key);
    return it == attributes.end() ? "" : it->second;
  }
  // Every element below (not including) this one named `element_name`
  // and, when `css_class` is not empty, of that class, in document order.
  std::vector<const XmlElement*> FindAll(
      const std::string& element_name,
      const std::string& css_class = "") const {
    std::vector<const XmlElement*> found;
    for (const XmlElement& child : children) {
      if (child.name == element_name &&
          (css_class.empty() || child.Attribute("class") == css_class)) {
        found.push_back(&child);
      }
      for (const XmlElement* below : child.FindAll(element_name, css_class)) {
        found.push_back(below);
      }
    }
    return found;
  }
};

class XmlReader {
 public:
  // The document's root, or nullopt with error() saying what is wrong.
  std::optional<XmlElement> Parse(std::string_view text) {
    text_ = text;
    at_ = 0;
    error_.clear();
    SkipSpace();
    if (Peek("<?xml")) {
      const size_t end = text_.find("?>", at_);
      if (end == std::string_view::npos) return Fail("unclosed declaration");
      at_ = end + 2;
    }
    SkipMisc();
    XmlElement root;
    if (!Element(&root)) return std::nullopt;
    SkipMisc();
    if (at_ != text_.size()) return Fail("content after the root element");
    return root;
  }
  const std::string& error() const { return error_; }

 private:
  std::nullopt_t Fail(const std::string& what) {
    if (error_.empty()) {
      error_ = what + " at offset " + std::to_string(at_);
    }
    return std::nullopt;
  }
  bool Peek(std::string_view s) const {
    return text_.substr(at_, s.size()) == s;
  }
  void SkipSpace() {
    while (at_ < text_.size() &&
           std::isspace(static_cast<unsigned char>(text_[at_]))) {
      ++at_;
    }
  }
  // Space and comments.
  void SkipMisc() {
    for (;;) {
      SkipSpace();
      if (!Peek("<!--")) return;
      const size_t end = text_.find("-->", at_ + 4);
      if (end == std::string_view::npos) {
        at_ = text_.size();
        Fail("unclosed comment");
        return;
      }
      at_ = end + 3;
    }
  }
  static bool NameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':';
  }
  static bool NameChar(char c) {
    return NameStart(c) || std::isdigit(static_cast<unsigned char>(c)) ||
           c == '-' || c == '.';
  }
  bool Name(std::string* name) {
    if (at_ >= text_.size() || !NameStart(text_[at_])) {
      Fail("expected a name");
      return false;
    }
    const size_t start = at_;
    while (at_ < text_.size() && NameChar(text_[at_])) ++at_;
    *name = std::string(text_.substr(start, at_ - start));
    return true;
  }
  // Decodes an entity or character reference at '&'.
  bool Reference(std::string* out) {
    const size_t end = text_.find(';', at_);
    if (end == std::string_view::npos || end - at_ > 10) {
      Fail("bare '&'");
      return false;
    }
    const std::string_view ref = text_.substr(at_ + 1, end - at_ - 1);
    static const std::map<std::string_view, char> kEntities = {
        {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
    if (auto it = kEntities.find(ref); it != kEntities.end()) {
      *out += it->second;
    } else if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string digits(ref.substr(hex ? 2 : 1));
      if (digits.empty()) {
        Fail("empty character reference");
        return false;
      }
      for (char c : digits) {
        if (hex ? !std::isxdigit(static_cast<unsigned char>(c))
                : !std::isdigit(static_cast<unsigned char>(c))) {
          Fail("bad character reference");
          return false;
        }
      }
      *out += '?';  // The tests never look at such characters.
    } else {
      Fail("unknown entity &" + std::string(ref) + ";");
      return false;
    }
    at_ = end + 1;
    return true;
  }
  bool Element(XmlElement* element) {
    if (!Peek("<")) {
      Fail("expected '<'");
      return false;
    }
    ++at_;
    if (!Name(&element->name)) return false;
    for (;;) {
      const size_t before = at_;
      SkipSpace();
      if (Peek("/>")) {
        at_ += 2;
        return true;
      }
      if (Peek(">")) {
        ++at_;
        break;
      }
      if (at_ == before) {
        Fail("expected space before an attribute");
        return false;
      }
      std::string key;
      if (!Name(&key)) return false;
      SkipSpace();
      if (!Peek("=")) {
        Fail("attribute " + key + " has no value");
        return false;
      }
      ++at_;
      SkipSpace();
      if (at_ >= text_.size() || (text_[at_] != '"' && text_[at_] != '\'')) {
        Fail("attribute " + key + " is not quoted");
        return false;
      }
      const char quote = text_[at_++];
      std::string value;
      while (at_ < text_.size() && text_[at_] != quote) {
        if (text_[at_] == '<') {
          Fail("'<' in an attribute value");
          return false;
        }
        if (text_[at_] == '&') {
          if (!Reference(&value)) return false;
        } else {
          value += text_[at_++];
        }
      }
      if (at_ >= text_.size()) {
        Fail("unclosed attribute value");
        return false;
      }
      ++at_;
      if (!element->attributes.emplace(key, value).second) {
        Fail("attribute " + key + " given twice");
        return false;
      }
    }
    // Content.
    for (;;) {
      if (at_ >= text_.size()) {
        Fail("unclosed element <" + element->name + ">");
        return false;
      }
      if (Peek("</")) {
        at_ += 2;
        std::string name;
        if (!Name(&name)) return false;
        SkipSpace();
        if (name != element->name || !Peek(">")) {
          Fail("</" + name + "> closes <" + element->name + ">");
          return false;
        }
        ++at_;
        return true;
      }
      if (Peek("<!--")) {
        const size_t end = text_.find("-->", at_ + 4);
        if (end == std::string_view::npos) {
          Fail("unclosed comment");
          return false;
        }
        at_ = end + 3;
      } else if (Peek("<")) {
        element->children.emplace_back();
        if (!Element(&element->children.back())) return false;
      } else if (text_[at_] == '&') {
        if (!Reference(&element->text)) return false;
      } else {
        element->text += text_[at_++];
      }
    }
  }

  std::string_view text_;
  size_t at_ = 0;
  std::string error_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_SVG_XML_H_
