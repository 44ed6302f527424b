#include "vantage/io/yaml_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include "temp_dir.hpp"

namespace vantage {
namespace {

/// The one-line message of the YamlError `action` throws.
std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const YamlError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no YamlError";
  return "";
}

constexpr const char* kText = R"(name: demo
grid:
  resolution: 0.01
  dims: [4, 5, 6]
flags: {a: yes, b: Off, c: maybe}
values: [1, +2.5, -3e2, .nan, -.inf, 0x10, '', [1]]
)";

TEST(YamlReader, ReadsTypedValuesAlongKeyPaths) {
  const YamlField root = parse_yaml(kText, "demo.yaml");
  root.allow_keys({"name", "grid", "flags", "values"});
  EXPECT_EQ(root.at("name").text(), "demo");
  const YamlField grid = root.at("grid");
  EXPECT_EQ(grid.key(), "grid");
  EXPECT_EQ(grid.at("resolution").positive(), 0.01);
  EXPECT_EQ(grid.at("dims").vec3(), Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(grid.at("dims")[2].integer(1, 6), 6);
  EXPECT_EQ(grid.at("dims")[2].key(), "grid.dims[2]");
  EXPECT_EQ(grid.at("dims")[2].line(), 4);
  EXPECT_TRUE(root.at("flags").at("a").boolean());
  EXPECT_FALSE(root.at("flags").at("b").boolean());
  EXPECT_FALSE(root.get("missing").has_value());
  EXPECT_TRUE(root.has("flags"));
  const YamlField values = root.at("values");
  EXPECT_EQ(values[0].number(), 1.0);
  EXPECT_EQ(values[1].number(), 2.5);
  EXPECT_EQ(values[2].number(), -300.0);
}

TEST(YamlReader, EveryMistakeIsOneLineWithFileLineAndKey) {
  const YamlField root = parse_yaml(kText, "demo.yaml");
  const YamlField values = root.at("values");
  const std::pair<std::function<void()>, std::string> cases[] = {
      {[&] {
         root.allow_keys({"name", "grid"});
       },
       "demo.yaml:5: flags: unknown key 'flags' (expected one of: name, grid)"},
      {[&] { root.at("grid").at("origin"); }, "demo.yaml:3: grid: missing key 'origin'"},
      {[&] { root.at("flags").at("c").boolean(); }, "demo.yaml:5: flags.c: must be true or false"},
      {[&] { values[3].number(); }, "demo.yaml:6: values[3]: is NaN"},
      {[&] { values[4].number(); }, "values[4]: is infinite"},
      {[&] { values[5].number(); }, "values[5]: '0x10' is not a number"},
      {[&] { values[6].text(); }, "values[6]: must not be empty"},
      {[&] { values[7].number(); }, "values[7]: must be a number"},
      {[&] { values[2].positive(); }, "values[2]: must be positive, got -300"},
      {[&] { values[1].integer(0, 10); }, "values[1]: must be a whole number in [0, 10], got 2.5"},
      {[&] { root.at("grid").at("dims").vec2(); }, "grid.dims: must be a list of 2 numbers"},
      {[&] { root.at("name").items(); }, "demo.yaml:1: name: must be a list"},
      {[&] { root.at("name").require_map(); }, "name: must be a map of keys"},
      {[&] { root.fail_as("", "said without a key"); }, "demo.yaml:1: said without a key"},
      {[&] { parse_yaml("a: [1, 2\n", "bad.yaml"); }, "bad.yaml:2: not valid YAML: "},
      {[&] { parse_yaml("? [a]\n: 1\n", "key.yaml"); }, "key.yaml:1: a map key must be a plain"},
      {[&] { parse_yaml("a:\n  b: 1\n  c: 2\n  b: 3\n", "d.yaml"); },
       "d.yaml:4: a.b: duplicate key 'b' (first at line 2)"},
      {[&] { parse_yaml("- {x: 1, x: 1}\n", "d.yaml"); }, "d.yaml:1: [0].x: duplicate key 'x'"},
      {[&] { parse_yaml("a: 1\n---\na: 2\n", "two.yaml"); }, "two.yaml:3: a second YAML document"},
      {[&] { parse_yaml("a: 1\n...\n---\n", "end.yaml"); }, "end.yaml:"},
      // issue 15, found by fuzz/scene_fuzzer.cpp: a key with a line break (there, a plain key
      // folded over a blank line), which the message must not echo.
      {[&] { parse_yaml("a:\n  \"e\\nf\": 1\n", "break.yaml"); },
       "break.yaml:2: a: a map key must be a plain name"},
      // issue 15, found by fuzz/manifest_fuzzer.cpp: yaml-cpp's LoadAll never returned on these.
      {[&] { parse_yaml(",", "comma.yaml"); }, "comma.yaml:1: not valid YAML"},
      // issue 15, found by fuzz/manifest_fuzzer.cpp: yaml-cpp's message quoted a line break.
      {[&] {
         constexpr char kBytes[] = "ud\x1c\0\n  - fame: x_forward\n   ";
         parse_yaml(std::string_view(kBytes, sizeof kBytes - 1), "escape.yaml");
       },
       "escape.yaml:2: not valid YAML: unknown escape character: \\x0a"},
      {[&] { parse_yaml("a: 1\n---\n, b\n", "comma.yaml"); },
       "comma.yaml:3: a second YAML document"},
  };
  for (const auto& [action, expected] : cases) {
    const std::string message = error_of(action);
    EXPECT_NE(message.find(expected), std::string::npos) << message << " | " << expected;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// issue 27: 100,000 nested brackets are said as what they are, not yaml-cpp's "bad file".
TEST(YamlReader, DeepNestingSaysSo) {
  const std::string deep = "a: " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  const std::string message = error_of([&] { parse_yaml(deep, "deep.yaml"); });
  EXPECT_NE(message.find("deep.yaml:1: not valid YAML here: nested more than"), std::string::npos)
      << message;
  EXPECT_EQ(message.find("bad file"), std::string::npos) << message;
}

TEST(YamlReader, AliasesStayShared) {
  // "Billion laughs": ten levels of ten aliases each would expand to 10^10 items.
  std::ostringstream text;
  for (int level = 0; level <= 9; ++level) {
    text << 'l' << level << ": &a" << level << " [";
    for (int k = 0; k < 10; ++k) {
      text << (k > 0 ? ", " : "");
      if (level == 0) {
        text << 'x';
      } else {
        text << "*a" << level - 1;
      }
    }
    text << "]\n";
  }
  const YamlField root = parse_yaml(text.str(), "laughs.yaml");
  YamlField deep = root.at("l9");
  for (int level = 9; level > 0; --level) {
    ASSERT_EQ(deep.size(), 10u);
    deep = deep[9];
  }
  EXPECT_EQ(deep[9].text(), "x");
  EXPECT_EQ(deep[9].key(), "l9[9][9][9][9][9][9][9][9][9][9]");
}

TEST(YamlReader, FilesAreNamedWhenTheyCannotBeRead) {
  test::TempDir dir;
  const std::string message = error_of([&] { read_yaml_file(dir / "nothing.yaml"); });
  EXPECT_NE(message.find("nothing.yaml: no such file"), std::string::npos) << message;
  test::write_file(dir / "ok.yaml", "a: 1\n");
  EXPECT_EQ(read_yaml_file(dir / "ok.yaml").at("a").number(), 1.0);
}

}  // namespace
}  // namespace vantage
