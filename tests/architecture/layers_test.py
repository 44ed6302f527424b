#!/usr/bin/env python3
"""The architecture's rules, held by the suite (docs/architecture.md):

- layers: every include under vantage/ runs to the file's own layer or one below it, as
  vantage/layers.txt writes the layers down;
- folders: a folder within a stage's (vantage/gain/models/, vantage/experiment/detail/, ...)
  holds the files of one layer, so that the folders read as the layers, and no file sits beside a
  folder of its own name (gain/metrics.hpp beside gain/metrics/);
- sizes: no source file of the library, the CLI or the bindings is over 400 lines, and the
  decision's entry point (vantage/planner/planner.cpp) is under 200;
- functions: no function there is over 80 lines, from the first line of its declaration to its
  closing brace. A function is a body at namespace or class scope, a lambda given a name there,
  or a lambda in an initializer there (a registry's row); a lambda inside a function is counted
  with that function.

Run as `layers_test.py REPO`. It first checks itself on a small tree with one include up a
layer and on a source whose functions it knows, so that a checker that cannot fail does not pass.
"""
import bisect
import fnmatch
import pathlib
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s+"vantage/([^"]+)"', re.M)
MAX_LINES = 400  # the most a file may have
ENTRY_POINT = ("vantage/planner/planner.cpp", 199)
MAX_FUNCTION_LINES = 80
SIZED = ("vantage", "apps", "python/src")
SOURCE = (".hpp", ".cpp", ".h")


def read_layers(path):
    """[(name, [patterns])], bottom first."""
    layers = []
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        name, _, patterns = line.partition(":")
        if not patterns.split():
            raise SystemExit(f"{path}: layer '{name}' has no pattern")
        layers.append((name.strip(), patterns.split()))
    return layers


def layer_of(relative, layers):
    """(rank, name) of the layer whose longest pattern matches `relative`, or None."""
    best = None
    for rank, (name, patterns) in enumerate(layers):
        for pattern in patterns:
            if fnmatch.fnmatchcase(relative, pattern):
                if best is None or len(pattern) > best[0]:
                    best = (len(pattern), rank, name)
    return None if best is None else best[1:]


def layer_violations(root):
    """Every include under root/vantage that runs up a layer, and every file in no layer."""
    layers = read_layers(root / "vantage" / "layers.txt")
    problems = []
    for path in sorted((root / "vantage").rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h"):
            continue
        relative = path.relative_to(root / "vantage").as_posix()
        mine = layer_of(relative, layers)
        if mine is None:
            problems.append(f"vantage/{relative}: in no layer of vantage/layers.txt")
            continue
        for included in INCLUDE.findall(path.read_text()):
            theirs = layer_of(included, layers)
            if theirs is None:
                problems.append(f"vantage/{relative}: includes vantage/{included}, in no layer")
            elif theirs[0] > mine[0]:
                problems.append(f"vantage/{relative} ({mine[1]}) includes vantage/{included} "
                                f"({theirs[1]}), a higher layer")
    return problems


def folder_violations(root):
    """Every folder within a stage's that spans layers, and every file named as a folder beside it."""
    layers = read_layers(root / "vantage" / "layers.txt")
    problems = []
    spans = {}
    for path in sorted((root / "vantage").rglob("*")):
        relative = path.relative_to(root / "vantage")
        if path.is_dir():
            if path.with_suffix(".hpp").exists() or path.with_suffix(".cpp").exists():
                problems.append(f"vantage/{relative.as_posix()}/ has a file of its name beside it")
            continue
        if path.suffix not in (".hpp", ".cpp", ".h") or len(relative.parts) < 3:
            continue
        mine = layer_of(relative.as_posix(), layers)
        if mine is not None:
            spans.setdefault("/".join(relative.parts[:2]), set()).add(mine[1])
    for folder, names in sorted(spans.items()):
        if len(names) > 1:
            problems.append(f"vantage/{folder}/ spans the layers {', '.join(sorted(names))}")
    return problems


def sized_sources(root):
    """(relative path, text) of every source file of the library, the CLI and the bindings."""
    for top in SIZED:
        for path in sorted((root / top).rglob("*")):
            if path.suffix in SOURCE:
                yield path.relative_to(root).as_posix(), path.read_text()


def size_violations(root):
    problems = []
    for relative, text in sized_sources(root):
        lines = len(text.splitlines())
        limit = ENTRY_POINT[1] if relative == ENTRY_POINT[0] else MAX_LINES
        if lines > limit:
            problems.append(f"{relative}: {lines} lines, at most {limit}")
    return problems


# Function lengths. The sources are clang-formatted, so it is enough to blank out comments,
# literals and preprocessor lines and to match braces, telling at namespace and class scope what
# each `{` opens from the declaration before it.

IDENTIFIER = re.compile(r"[A-Za-z0-9_]")
ACCESS = re.compile(r"(public|private|protected)\s*:\s*")
OPERATOR = re.compile(r"operator\s*(\(\)|[^\s(]+)")
# what may follow a function's `)`: qualifiers and a trailing return type
QUALIFIERS = re.compile(
    r"(\s*(const|noexcept(\s*\([^()]*\))?|override|final|mutable|constexpr|&&|&|"
    r"->\s*[\w:<>,\s*&]+))+\s*$")
# a lambda's introducer up to its body: captures, parameters, specifiers, return type
LAMBDA = re.compile(r"\[[^\[\]]*\]\s*(\([^()]*(\([^()]*\)[^()]*)*\))?"
                    r"(\s*(mutable|constexpr|noexcept|->\s*[\w:<>,\s*&]+))*\s*$")


def blank_code(text):
    """`text` with comments, string and character literals and preprocessor lines turned to
    spaces, its newlines kept, so that braces can be matched and offsets read as lines."""
    out = list(text)

    def blank(begin, end):
        for k in range(begin, end):
            if out[k] != "\n":
                out[k] = " "

    i, n, line_start = 0, len(text), True
    while i < n:
        c = text[i]
        if c == "\n" or (line_start and c in " \t"):
            line_start = c == "\n" or line_start
            i += 1
            continue
        if line_start and c == "#":  # a preprocessor line, with its continuations
            j = i
            while j < n and (text[j] != "\n" or text[j - 1] == "\\"):
                j += 1
            blank(i, j)
            i = j
            continue
        line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            blank(i, j)
        elif c == '"':
            raw = re.search(r"(?<![\w])(?:u8|u|U|L)?R$", text[max(0, i - 3):i])
            if raw:  # R"delimiter( ... )delimiter"
                delimiter = text[i + 1:text.index("(", i)]
                j = text.index(")" + delimiter + '"', i) + len(delimiter) + 2
            else:
                j = i + 1
                while text[j] != '"':
                    j += 2 if text[j] == "\\" else 1
                j += 1
            blank(i + 1, j - 1)
        elif c == "'":
            k = i - 1
            while k >= 0 and IDENTIFIER.match(text[k]):
                k -= 1
            if k < i - 1 and text[k + 1].isdigit():  # a digit separator: 1'000
                i += 1
                continue
            j = i + 1
            while text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            j += 1
            blank(i + 1, j - 1)
        else:
            j = i + 1
        i = j
    return "".join(out)


def strip_template(header):
    """`header` without its leading `template <...>`s."""
    m = re.match(r"template\s*<", header)
    if not m:
        return header
    depth, i = 1, m.end()
    while i < len(header) and depth:
        depth += {"<": 1, ">": -1}.get(header[i], 0)
        i += 1
    return strip_template(header[i:].lstrip())


def top_level(header):
    """`header` without its operators' symbols and what is inside (), [] and {}."""
    out, depth = [], 0
    for c in OPERATOR.sub("operator", header):
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif depth == 0:
            out.append(c)
    return "".join(out)


def declared_name(header):
    """The (qualified) name `header`, a declaration up to its `{`, declares."""
    flat = top_level(header)
    if "=" in flat:  # a variable: an initializer, or a lambda given a name
        m = re.search(r"([\w:]+)\s*=", flat)
        return m.group(1) if m else "?"
    flat = re.sub(r"<[^<>()]*>", "", strip_template(header))  # template arguments, one level
    m = re.search(r"((?:[\w~]+\s*::\s*)*)(operator\s*(?:\(\)|[^\s(]+)|[\w~]+)\s*\(", flat)
    return re.sub(r"\s+", "", m.group(1) + m.group(2)) if m else "?"


def opens(header):
    """What a `{` at namespace or class scope opens, given its declaration `header`: a
    "namespace", a "class", a "function" or an "initializer" (any other braces)."""
    header = strip_template(header.strip())
    if re.match(r"(inline\s+)?namespace\b|extern\b", header):
        return "namespace"
    flat = top_level(header)
    if re.match(r"(class|struct|union)\b", header) and "(" not in flat and "=" not in flat:
        return "class"
    if "=" in flat:
        return "function" if LAMBDA.search(header) else "initializer"
    if re.match(r"enum\b", header):
        return "initializer"
    head = QUALIFIERS.sub("", header)
    # a constructor's body follows its initializer list, whose last member may take braces
    if head.endswith(")") or (head.endswith("}") and re.search(r"\)\s*:", header)):
        return "function"
    return "initializer"


def functions(text):
    """[(name, first line, last line)] of every function in `text`, a clang-formatted source, as
    the module's docstring defines them."""
    code = blank_code(text)
    found = []
    # the open scopes, innermost last: [what it is, where the declaration being read in it
    # starts, its name, where its own declaration started]
    stack = [["namespace", 0, None, None]]
    for i, c in enumerate(code):
        top = stack[-1]
        if top[0] in ("function", "block"):  # inside a function, braces are only counted
            if c == "{":
                stack.append(["block", None, None, None])
            elif c == "}" and stack.pop()[0] == "function":
                found.append((top[2], top[3], i))
                if stack[-1][0] != "initializer":
                    stack[-1][1] = i + 1
            continue
        if c == ";":
            top[1] = i + 1
        elif c == "{":
            header = code[top[1]:i]
            start = top[1] + len(header) - len(header.lstrip())
            access = ACCESS.match(code, start)
            if access:
                start, header = access.end(), code[access.end():i]
            if top[0] == "initializer":  # a lambda in a row, or braces in braces
                lam = LAMBDA.search(header)
                if lam:
                    stack.append(["function", None, f"{top[2]} (a lambda)", top[1] + lam.start()])
                else:
                    stack.append(["initializer", i + 1, top[2], None])
                continue
            stack.append([opens(header), i + 1, declared_name(header.strip()), start])
        elif c == "}":
            closed = stack.pop()
            # braces in a constructor's initializer list or a variable's initializer leave the
            # declaration open
            if closed[0] != "initializer" and stack[-1][0] != "initializer":
                stack[-1][1] = i + 1
    if len(stack) != 1:
        raise ValueError(f"braces do not match: {[scope[0] for scope in stack]} left open")
    newlines = [k for k, ch in enumerate(code) if ch == "\n"]
    line = lambda offset: bisect.bisect_left(newlines, offset) + 1
    return [(name, line(begin), line(end)) for name, begin, end in found]


def function_violations(root):
    problems = []
    for relative, text in sized_sources(root):
        for name, first, last in functions(text):
            length = last - first + 1
            if length > MAX_FUNCTION_LINES:
                problems.append(f"{relative}:{first}: {name} is {length} lines, at most "
                                f"{MAX_FUNCTION_LINES}")
    return problems


def self_check():
    """The checker finds an include up a layer and a file in no layer, and passes a clean tree."""
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "vantage" / "low").mkdir(parents=True)
        (root / "vantage" / "high").mkdir()
        (root / "vantage" / "layers.txt").write_text("low: low/*\nhigh: high/*\n")
        (root / "vantage" / "high" / "h.hpp").write_text('#include "vantage/low/l.hpp"\n')
        (root / "vantage" / "low" / "l.hpp").write_text("// nothing\n")
        assert layer_violations(root) == [], layer_violations(root)
        (root / "vantage" / "low" / "l.hpp").write_text('#include "vantage/high/h.hpp"\n')
        (root / "vantage" / "other.hpp").write_text("\n")
        found = layer_violations(root)
        assert any("includes vantage/high/h.hpp (high), a higher layer" in p for p in found), found
        assert any("other.hpp: in no layer" in p for p in found), found
        assert folder_violations(root) == [], folder_violations(root)
        (root / "vantage" / "layers.txt").write_text("low: low/*\nhigh: high/* low/sub/h*\n")
        (root / "vantage" / "low" / "sub").mkdir()
        (root / "vantage" / "low" / "sub" / "l.hpp").write_text("\n")
        (root / "vantage" / "low" / "sub" / "h.hpp").write_text("\n")
        (root / "vantage" / "low" / "sub.hpp").write_text("\n")
        found = folder_violations(root)
        assert any("low/sub/ spans the layers high, low" in p for p in found), found
        assert any("low/sub/ has a file of its name" in p for p in found), found

    assert functions(KNOWN_FUNCTIONS) == KNOWN, functions(KNOWN_FUNCTIONS)
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "vantage").mkdir()
        body = "".join(f"  x += {k};\n" for k in range(MAX_FUNCTION_LINES - 2))
        (root / "vantage" / "f.cpp").write_text(f"void fits(int x) {{\n{body}}}\n")
        assert function_violations(root) == [], function_violations(root)
        (root / "vantage" / "f.cpp").write_text(f"void long_one(int x) {{\n{body}  ++x;\n}}\n")
        found = function_violations(root)
        assert found == [f"vantage/f.cpp:1: long_one is {MAX_FUNCTION_LINES + 1} lines, at most "
                         f"{MAX_FUNCTION_LINES}"], found


# A source that trips a naive brace counter, and the functions in it.
KNOWN_FUNCTIONS = r'''
// a { in a comment
#define OPEN { \
  }
namespace a::b {
extern "C" {
int c_function(int x) {
  return x;
}
}
const char* kRaw = R"js(function f() { return "}"; })js";
const char kBrace = '{';
const int kBig = 1'000'000;
enum class E : int { kA, kB };
constexpr std::array kRows = {
    Row{"a", [](int x) {
          return x + 1;
        }},
    Row{"b", nullptr},
};
const auto kHelper = [](int y) -> int {
  return y * 2;
};
template <typename T = int>
struct S : Base<void(int)> {
 public:
  S(int x) : a_{x}, b_(x) {
    if (x) {
      a_ = 1;
    }
  }
  bool operator==(const S& o) const { return a_ == o.a_; }
  int a_{0};
  int b_ = 1;
  struct Inner {
    void f() {}
  };
};
std::vector<int> g(int x = 3,
                   const std::string& s = "{") noexcept {
  auto l = [&](int k) {
    return k;
  };
  return {l(x)};
}
template <typename T>
T S<T>::h() const {
  return T{};
}
PYBIND11_MODULE(m, module) {
  module.def("f", [](int x) { return x; });
}
}  // namespace a::b
'''
KNOWN = [("c_function", 7, 9), ("kRows (a lambda)", 16, 18), ("kHelper", 21, 23), ("S", 27, 31),
         ("operator==", 32, 32), ("f", 36, 36), ("g", 39, 45), ("S::h", 46, 49),
         ("PYBIND11_MODULE", 50, 52)]


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    self_check()
    checks = {"layers": layer_violations(root), "folders": folder_violations(root),
              "sizes": size_violations(root),
              "functions": function_violations(root)}
    failed = 0
    for name, problems in checks.items():
        for problem in problems:
            print(f"FAIL ({name}): {problem}")
        failed += 1 if problems else 0
    print(f"{len(checks) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
