// A streaming tokenizer for the XML grammar lib3mf 1.8.1 reads (CXmlReader_Native), fed the
// inflated bytes of a 3MF part so it can be screened before lib3mf reads it.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace strand::slicer {

// One attribute an XmlSink is given: id, objectid, path, Type, Target, requiredextensions
// and namespace declarations (xmlns, xmlns:p) with their values; any other prefixed one
// with its prefix and an empty value (so undeclared prefixes can be found).
struct XmlAttr {
  bool prefixed = false;
  std::string name;  // local name
  std::string value;
  std::string prefix;  // "p" of "p:name"; empty when not prefixed
};

// Calls for the start and end tags of a document.
class XmlSink {
 public:
  virtual ~XmlSink() = default;
  // `prefix`: the element's namespace prefix ("m" of <m:texture2d>), empty when none.
  virtual void start(const std::string& name, const std::string& prefix,
                     const std::vector<XmlAttr>& attrs, bool self_closing) = 0;
  virtual void end() = 0;
};

// lib3mf's XML grammar, fed in pieces. Stops (broken()) where lib3mf's reader throws; throws
// std::length_error for an element with more than kMaxKeptAttrs attributes given to the sink.
class XmlTokens {
 public:
  explicit XmlTokens(XmlSink& sink) : sink_(sink) {}

  void feed(const char* p, std::size_t n) {
    for (std::size_t i = 0; i < n && state_ != State::Broken; ++i, ++offset_) step(p[i]);
  }
  bool broken() const { return state_ == State::Broken; }
  // Byte offset, in everything fed, just past the first element's name ("<model|"), where
  // attributes can be inserted; npos before it is read.
  std::size_t root_name_end() const { return root_name_end_; }

 private:
  enum class State {
    Text,
    Name,
    Comment,
    PiName,
    EndName,
    Attrs,
    AttrName,
    AttrNameSpaced,
    ValueStart,
    Value,
    CloseElement,
    ClosePi,
    Broken
  };
  static constexpr std::size_t kMaxName = 256;
  static constexpr std::size_t kMaxValue = 65536;
  static constexpr std::size_t kMaxKeptAttrs = 64;

  void append(std::string& s, char c, std::size_t cap);
  void begin_element();
  void finish_attr();
  void finish_start(bool self_closing);
  void step(char c);

  XmlSink& sink_;
  State state_ = State::Text;
  std::string name_, element_, element_prefix_, attr_name_, value_;
  std::size_t offset_ = 0, root_name_end_ = static_cast<std::size_t>(-1);
  std::vector<XmlAttr> attrs_;
  bool long_ = false, value_long_ = false, value_spaced_ = false, in_pi_ = false;
  char quote_ = '"';
  int comment_ = 0;
  std::size_t ends_ = 0;
};

}  // namespace strand::slicer
