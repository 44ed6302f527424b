#pragma once
/// @file
/// The one strict reader of Vantage's YAML files (scene files, manifests): every key checked,
/// every value typed, and every problem one line "file:line: key: what".

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vantage {

/// A problem in a YAML file, in one line that starts with the file and line.
struct YamlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A node of a YAML document with the key path that leads to it ("objects[2].size"), so that
/// every error names the file, the line and the key. Cheap to copy; copies share the document.
/// Every accessor that finds the wrong kind or value throws YamlError.
class YamlField {
 public:
  struct Node;  ///< the document's node (yaml-cpp stays inside yaml_reader.cpp)

  YamlField(std::shared_ptr<const Node> node, std::string key,
            std::shared_ptr<const std::string> source);

  const std::string& key() const { return key_; }  ///< empty at the document's root
  int line() const;                                ///< 1-based; 0 when unknown

  /// Throws YamlError "source:line: key: what" (without "key: " at the root).
  [[noreturn]] void fail(std::string_view what) const;
  /// fail with this node's line but another key (none when empty): for a problem of a key that
  /// is absent, or a message that names its keys itself.
  [[noreturn]] void fail_as(std::string_view key, std::string_view what) const;

  bool is_map() const;
  bool is_sequence() const;
  bool is_scalar() const;

  /// Fails unless this is a map ("must be a map of keys").
  void require_map() const;
  /// A map whose keys are all among `allowed`; an unknown key (a typo) fails at that key,
  /// naming the allowed ones.
  void allow_keys(std::initializer_list<std::string_view> allowed) const;
  /// Whether this map has `key` (present with any value, null included).
  bool has(std::string_view key) const;
  /// The value of `key` in this map, or nothing when the key is absent.
  std::optional<YamlField> get(std::string_view key) const;
  /// The value of `key`; fails "missing key 'key'" when absent.
  YamlField at(std::string_view key) const;

  /// Number of items of a sequence (or entries of a map).
  std::size_t size() const;
  /// Item `i` of a sequence, keyed "key[i]".
  YamlField operator[](std::size_t i) const;
  /// The items of a sequence; fails "must be a list" otherwise.
  std::vector<YamlField> items() const;

  /// A non-empty scalar's text.
  std::string text() const;
  /// A finite number ("is NaN", "is infinite" and "'x' is not a number" otherwise).
  double number() const;
  double positive() const;      ///< a number > 0
  double non_negative() const;  ///< a number >= 0
  /// A whole number in [min, max].
  int integer(int min, int max) const;
  /// true/false (also yes/no, on/off, y/n in YAML's spellings).
  bool boolean() const;
  /// A list of min_count to max_count numbers.
  std::vector<double> numbers(std::size_t min_count, std::size_t max_count) const;
  Eigen::Vector2d vec2() const;           ///< [x, y]
  Eigen::Vector3d vec3() const;           ///< [x, y, z]
  Eigen::Vector2d positive_vec2() const;  ///< [x, y], each > 0
  Eigen::Vector3d positive_vec3() const;  ///< [x, y, z], each > 0

 private:
  YamlField child(const std::shared_ptr<const Node>& node, std::string key) const;

  std::shared_ptr<const Node> node_;
  std::string key_;
  std::shared_ptr<const std::string> source_;
};

/// Parses `text` as one YAML document and returns its root; `source` names the text in messages
/// (a file's path, or "scene tabletop-1"). Refuses, with one line naming the line and key, text
/// that is not valid YAML, a second document, a key given twice in one map, and a map key that
/// is not a plain scalar. Anchors and aliases are kept shared, never expanded.
YamlField parse_yaml(std::string_view text, const std::string& source);

/// parse_yaml of the file at `path`, opened by read_input_file as settings (a regular file of at
/// most kMaxSettingsFileBytes); a file that cannot be read fails naming it, and one whose first
/// bytes name another format (a PCD cloud, an OctoMap...) says so, as "is X, not `what`".
YamlField read_yaml_file(const std::filesystem::path& path, std::string_view what = "YAML");

}  // namespace vantage
