#include "vantage/io/yaml_reader.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

/// The document as plain values, converted from yaml-cpp's nodes once.
struct YamlField::Node {
  enum class Kind { kNull, kScalar, kSequence, kMap };
  struct Entry {
    std::string key;  ///< of a map entry; empty for a sequence item
    int key_line = 0;
    std::shared_ptr<const Node> value;
  };
  Kind kind = Kind::kNull;
  std::string scalar;
  int line = 0;  ///< 1-based, 0 when unknown
  std::vector<Entry> entries;

  const Entry* find(std::string_view key) const {
    for (const Entry& entry : entries) {
      if (entry.key == key) return &entry;
    }
    return nullptr;
  }
};

namespace {
using Node = YamlField::Node;

std::string where(const std::string& source, int line) {
  return line > 0 ? cat(source, ":", line) : source;
}

[[noreturn]] void throw_error(const std::string& source, int line, std::string_view key,
                              std::string_view what) {
  // NOTE: keys and values echoed from the file may hold line breaks (a quoted "\n", a plain
  // scalar folded over blank lines) or binary; the message stays one line.
  throw YamlError(cat(where(source, line), ": ", printable(key, 200), key.empty() ? "" : ": ",
                      printable(what, 500)));
}

std::string child_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : cat(parent, ".", key);
}

/// Converts yaml-cpp's nodes, keeping an anchored node that aliases repeat as one shared node,
/// so that the work and memory stay linear in the text (no "billion laughs").
class Converter {
 public:
  explicit Converter(const std::string& source) : source_(source) {}

  std::shared_ptr<const Node> convert(const YAML::Node& in, const std::string& key, int line) {
    const YAML::Mark mark = in.Mark();
    const bool collection = in.IsSequence() || in.IsMap();
    if (collection) {
      const auto seen = shared_.find(mark.pos);
      if (seen != shared_.end() && seen->second.first.is(in)) return seen->second.second;
    }
    auto node = std::make_shared<Node>();
    node->line = in.IsNull() || mark.line < 0 ? line : mark.line + 1;
    if (in.IsScalar()) {
      node->kind = Node::Kind::kScalar;
      node->scalar = in.Scalar();
    } else if (in.IsSequence()) {
      node->kind = Node::Kind::kSequence;
      for (std::size_t i = 0; i < in.size(); ++i) {
        node->entries.push_back({"", node->line, convert(in[i], cat(key, "[", i, "]"), line)});
      }
    } else if (in.IsMap()) {
      node->kind = Node::Kind::kMap;
      for (const auto& item : in) {
        const int key_line = item.first.Mark().line + 1;
        // NOTE: a key with a line break or another control character (a plain scalar folded
        // over a blank line, found by fuzz/scene_fuzzer.cpp) is never one of ours, and echoing it
        // would break the one-line message.
        if (!item.first.IsScalar() ||
            std::any_of(item.first.Scalar().begin(), item.first.Scalar().end(),
                        [](unsigned char c) { return c < 0x20 || c == 0x7f; })) {
          throw_error(source_, key_line, key, "a map key must be a plain name");
        }
        const std::string name = item.first.Scalar();
        // NOTE: yaml-cpp keeps both entries of a key given twice and finds the first: a silent
        // choice between two values, refused here.
        if (const Node::Entry* first = node->find(name)) {
          throw_error(source_, key_line, child_key(key, name),
                      cat("duplicate key '", name, "' (first at line ", first->key_line, ")"));
        }
        node->entries.push_back(
            {name, key_line, convert(item.second, child_key(key, name), key_line)});
      }
    }
    if (collection) shared_.emplace(mark.pos, std::pair(in, node));
    return node;
  }

 private:
  const std::string& source_;
  /// Collections converted so far, by position in the text (checked to be the same node).
  std::map<int, std::pair<YAML::Node, std::shared_ptr<const Node>>> shared_;
};

/// Where a document's first node starts; the rest of the document is only parsed.
class FirstNodeMark : public YAML::EventHandler {
 public:
  YAML::Mark mark = YAML::Mark::null_mark();

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& at, YAML::anchor_t) override { note(at); }
  void OnAlias(const YAML::Mark& at, YAML::anchor_t) override { note(at); }
  void OnScalar(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                const std::string&) override {
    note(at);
  }
  void OnSequenceStart(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    note(at);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& at, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    note(at);
  }
  void OnMapEnd() override {}

 private:
  void note(const YAML::Mark& at) {
    if (!seen_) mark = at;
    seen_ = true;
  }
  bool seen_ = false;
};

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

YamlField::YamlField(std::shared_ptr<const Node> node, std::string key,
                     std::shared_ptr<const std::string> source)
    : node_(std::move(node)), key_(std::move(key)), source_(std::move(source)) {}

YamlField YamlField::child(const std::shared_ptr<const Node>& node, std::string key) const {
  return YamlField(node, std::move(key), source_);
}

int YamlField::line() const { return node_->line; }

void YamlField::fail(std::string_view what) const { fail_as(key_, what); }

void YamlField::fail_as(std::string_view key, std::string_view what) const {
  throw_error(*source_, node_->line, key, what);
}

bool YamlField::is_map() const { return node_->kind == Node::Kind::kMap; }
bool YamlField::is_sequence() const { return node_->kind == Node::Kind::kSequence; }
bool YamlField::is_scalar() const { return node_->kind == Node::Kind::kScalar; }

void YamlField::require_map() const {
  if (!is_map()) fail("must be a map of keys");
}

void YamlField::allow_keys(std::initializer_list<std::string_view> allowed) const {
  require_map();
  for (const Node::Entry& entry : node_->entries) {
    if (std::find(allowed.begin(), allowed.end(), entry.key) == allowed.end()) {
      std::string list;
      for (const std::string_view a : allowed) list += cat(list.empty() ? "" : ", ", a);
      throw_error(
          *source_, entry.key_line, child_key(key_, entry.key),
          cat("unknown key '", printable(entry.key, 40), "' (expected one of: ", list, ")"));
    }
  }
}

bool YamlField::has(std::string_view key) const { return is_map() && node_->find(key); }

std::optional<YamlField> YamlField::get(std::string_view key) const {
  require_map();
  const Node::Entry* entry = node_->find(key);
  if (entry == nullptr) return std::nullopt;
  return child(entry->value, child_key(key_, key));
}

YamlField YamlField::at(std::string_view key) const {
  if (auto value = get(key)) return *value;
  fail(cat("missing key '", key, "'"));
}

std::size_t YamlField::size() const { return node_->entries.size(); }

YamlField YamlField::operator[](std::size_t i) const {
  if (!is_sequence() || i >= size()) fail(cat("has no item ", i));
  return child(node_->entries[i].value, cat(key_, "[", i, "]"));
}

std::vector<YamlField> YamlField::items() const {
  if (!is_sequence()) fail("must be a list");
  std::vector<YamlField> out;
  for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i]);
  return out;
}

std::string YamlField::text() const {
  if (!is_scalar()) fail("must be a single value");
  if (node_->scalar.empty()) fail("must not be empty");
  return node_->scalar;
}

double YamlField::number() const {
  if (!is_scalar()) fail("must be a number");
  const std::string& text = node_->scalar;
  const std::string l = lower(text);
  if (l == ".nan") fail("is NaN");
  if (l == ".inf" || l == "+.inf" || l == "-.inf") fail("is infinite");
  const std::optional<double> value = parse_number(text);
  if (!value) fail(cat("'", printable(text, 40), "' is not a number"));
  if (std::isnan(*value)) fail("is NaN");
  if (std::isinf(*value)) fail("is infinite");
  return *value;
}

double YamlField::positive() const {
  const double v = number();
  if (!(v > 0.0)) fail(cat("must be positive, got ", v));
  return v;
}

double YamlField::non_negative() const {
  const double v = number();
  if (!(v >= 0.0)) fail(cat("must be >= 0, got ", v));
  return v;
}

int YamlField::integer(int min, int max) const {
  const double v = number();
  if (v != std::floor(v) || v < min || v > max) {
    fail(cat("must be a whole number in [", min, ", ", max, "], got ", v));
  }
  return static_cast<int>(v);
}

bool YamlField::boolean() const {
  // NOTE: the spellings yaml-cpp's own conversion takes.
  static constexpr std::string_view kTrue[] = {"y",    "Y",    "yes", "Yes", "YES", "true",
                                               "True", "TRUE", "on",  "On",  "ON"};
  static constexpr std::string_view kFalse[] = {"n",     "N",     "no",  "No",  "NO", "false",
                                                "False", "FALSE", "off", "Off", "OFF"};
  if (is_scalar()) {
    const std::string_view s = node_->scalar;
    if (std::find(std::begin(kTrue), std::end(kTrue), s) != std::end(kTrue)) return true;
    if (std::find(std::begin(kFalse), std::end(kFalse), s) != std::end(kFalse)) return false;
  }
  fail("must be true or false");
}

std::vector<double> YamlField::numbers(std::size_t min_count, std::size_t max_count) const {
  if (!is_sequence() || size() < min_count || size() > max_count) {
    fail(min_count == max_count
             ? cat("must be a list of ", min_count, " numbers")
             : cat("must be a list of ", min_count, " to ", max_count, " numbers"));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < size(); ++i) out.push_back((*this)[i].number());
  return out;
}

Eigen::Vector2d YamlField::vec2() const {
  const auto v = numbers(2, 2);
  return {v[0], v[1]};
}

Eigen::Vector3d YamlField::vec3() const {
  const auto v = numbers(3, 3);
  return {v[0], v[1], v[2]};
}

Eigen::Vector2d YamlField::positive_vec2() const {
  const Eigen::Vector2d v = vec2();
  for (std::size_t i = 0; i < 2; ++i) (*this)[i].positive();
  return v;
}

Eigen::Vector3d YamlField::positive_vec3() const {
  const Eigen::Vector3d v = vec3();
  for (std::size_t i = 0; i < 3; ++i) (*this)[i].positive();
  return v;
}

YamlField parse_yaml(std::string_view text, const std::string& source) {
  auto shared_source = std::make_shared<const std::string>(source);
  const std::string owned(text);
  YAML::Node root;
  try {
    // NOTE: YAML::Load reads the first document and ignores the rest without a word, and
    // yaml-cpp 0.7's LoadAll never returns on a stray ',' outside a flow collection (each
    // document it reads there is an empty one that consumes nothing, and memory grows without
    // bound; found by fuzz/manifest_fuzzer.cpp). So the documents are counted, two at most, by
    // where their first node starts, and then the first is loaded.
    std::istringstream in(owned);
    YAML::Parser parser(in);
    FirstNodeMark first, second;
    if (parser.HandleNextDocument(first) && parser.HandleNextDocument(second)) {
      const int line = second.mark.line >= 0 ? second.mark.line + 1 : 0;
      if (second.mark.pos == first.mark.pos) {
        throw_error(source, line, "", "not valid YAML: nothing can be read from here on");
      }
      throw_error(source, line, "", "a second YAML document (after '---'): the file must hold one");
    }
    root = YAML::Load(owned);
  } catch (const YAML::DeepRecursion& e) {
    // NOTE: yaml-cpp gives this one the message "bad file".
    throw_error(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, "",
                cat("not valid YAML here: nested more than ", e.depth() - 1,
                    " levels deep (no manifest or scene needs more than a few)"));
  } catch (const YAML::Exception& e) {
    throw_error(source, e.mark.line >= 0 ? e.mark.line + 1 : 0, "",
                cat("not valid YAML: ", printable(e.msg, 200)));
  }
  Converter converter(*shared_source);
  return YamlField(converter.convert(root, "", 1), "", shared_source);
}

YamlField read_yaml_file(const std::filesystem::path& path, std::string_view what) {
  std::string text;
  try {
    text = read_input_file(path, InputKind::kSettings);
  } catch (const FormatError& e) {
    throw YamlError(cat(path.string(), ": ", e.what()));
  }
  // NOTE: a cloud or a map given where settings belong is said as what it is, not as YAML's
  // complaint about its bytes ("unknown escape character").
  if (const std::string_view format = sniff_format(text); !format.empty() && format != "JSON") {
    throw YamlError(cat(path.string(), ": is ", format, ", not ", what));
  }
  return parse_yaml(text, path.string());
}

}  // namespace vantage
