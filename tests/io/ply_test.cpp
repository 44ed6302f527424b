#include "vantage/io/ply.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace vantage {
namespace {

/// Every value of every instance read, in file order, as (element, instance, values).
struct Read {
  std::size_t element;
  std::uint64_t index;
  std::vector<double> values;
};

std::vector<Read> read_all(const PlyReader& ply, std::size_t last) {
  std::vector<Read> out;
  ply.read(last, [&](std::size_t e, std::uint64_t i, const PlyRecord& r) {
    Read read{e, i, {}};
    const PlyElement& element = ply.elements()[e];
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      if (element.properties[k].is_list) {
        const auto items = r.list(k);
        read.values.push_back(static_cast<double>(items.size()));
        read.values.insert(read.values.end(), items.begin(), items.end());
      } else {
        read.values.push_back(r.scalar(k));
      }
    }
    out.push_back(read);
  });
  return out;
}

/// The message of the FormatError that reading all of `bytes` throws.
std::string error_of(const std::string& bytes) {
  try {
    const PlyReader ply(bytes);
    if (!ply.elements().empty()) read_all(ply, ply.elements().size() - 1);
  } catch (const FormatError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error for: " << bytes;
  return "";
}

/// A value as ASCII PLY writes it: whole numbers without a fraction.
std::string text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

constexpr ScalarType kAllTypes[] = {{'I', 1}, {'U', 1}, {'I', 2}, {'U', 2},
                                    {'I', 4}, {'U', 4}, {'F', 4}, {'F', 8}};

/// Appends `value` as a scalar of `type`, little- or big-endian: as the first of the types T
/// whose kind and size match.
template <typename... T>
void put_as_one_of(std::string& out, const ScalarType& type, double value, bool big) {
  const auto put = [&]<typename U>(U*) {
    const char kind = std::is_floating_point_v<U> ? 'F' : (std::is_signed_v<U> ? 'I' : 'U');
    if (kind != type.kind || type.size != static_cast<int>(sizeof(U))) return false;
    const U v = static_cast<U>(value);
    char bytes[sizeof(U)];
    std::memcpy(bytes, &v, sizeof(U));
    for (std::size_t i = 0; i < sizeof(U); ++i) out.push_back(bytes[big ? sizeof(U) - 1 - i : i]);
    return true;
  };
  (put(static_cast<T*>(nullptr)) || ...);
}

void put(std::string& out, const ScalarType& type, double value, bool big) {
  put_as_one_of<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t, std::uint32_t,
                float, double>(out, type, value, big);
}

// Oracle: a file built from a known element list and known values, written through ply_header
// in each encoding, reads back to exactly those elements and values.
TEST(PlyReader, EveryTypeAndListInEveryEncodingReadsBackExactly) {
  std::vector<PlyProperty> properties;
  for (const ScalarType& t : kAllTypes) properties.push_back({"p", t});
  properties.push_back({"l", {'I', 4}, true, {'U', 1}});
  const std::vector<PlyElement> elements = {{"vertex", 3, properties},
                                            {"extra", 2, {{"q", {'F', 8}}}}};
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> small(-100, 100), length(0, 4);
  std::vector<std::vector<double>> values;  // per instance, as read_all lists them
  for (const PlyElement& e : elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      std::vector<double> v;
      for (const PlyProperty& p : e.properties) {
        if (p.is_list) {
          const int n = length(rng);
          v.push_back(n);
          for (int j = 0; j < n; ++j) v.push_back(small(rng));
        } else {
          const double x = small(rng);
          v.push_back(p.type.kind == 'U' ? std::abs(x) : (p.type.kind == 'F' ? x / 4 : x));
        }
      }
      values.push_back(v);
    }
  }
  for (const PlyFormat format :
       {PlyFormat::kAscii, PlyFormat::kBinaryLittleEndian, PlyFormat::kBinaryBigEndian}) {
    std::string bytes = ply_header(format, {"made by a test"}, elements);
    std::size_t row = 0;
    for (const PlyElement& e : elements) {
      for (std::uint64_t i = 0; i < e.count; ++i, ++row) {
        std::size_t at = 0;
        for (const PlyProperty& p : e.properties) {
          const std::size_t items = p.is_list ? static_cast<std::size_t>(values[row][at]) : 0;
          if (format == PlyFormat::kAscii) {
            for (std::size_t j = 0; j <= items; ++j) bytes += text(values[row][at + j]) + " ";
          } else {
            const bool big = format == PlyFormat::kBinaryBigEndian;
            if (p.is_list) put(bytes, p.count_type, static_cast<double>(items), big);
            for (std::size_t j = p.is_list ? 1 : 0; j <= items; ++j) {
              put(bytes, p.type, values[row][at + j], big);
            }
          }
          at += items + 1;
        }
        if (format == PlyFormat::kAscii) bytes += "\n";
      }
    }
    const PlyReader ply(bytes);
    EXPECT_EQ(ply.format(), format);
    ASSERT_EQ(ply.elements().size(), 2u);
    EXPECT_EQ(ply.elements()[0].properties.size(), properties.size());
    EXPECT_EQ(ply.elements()[1].count, 2u);
    const std::vector<Read> read = read_all(ply, 1);
    ASSERT_EQ(read.size(), values.size());
    for (std::size_t r = 0; r < read.size(); ++r) EXPECT_EQ(read[r].values, values[r]) << r;
    EXPECT_EQ(read[4].element, 1u);
    EXPECT_EQ(read[4].index, 1u);
  }
}

TEST(PlyReader, ReadsOnlyUpToTheLastElementAsked) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n1.5\n";
  const std::string bytes = head + "3 0 0 oops\n";  // the reader keeps a view of it
  const PlyReader ply(bytes);
  const std::vector<Read> vertices = read_all(ply, 0);
  ASSERT_EQ(vertices.size(), 1u);
  EXPECT_EQ(vertices[0].values, std::vector<double>{1.5});
  EXPECT_THROW(read_all(ply, 1), FormatError);
}

TEST(PlyReader, MalformedFilesSayWhatAndWhere) {
  const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 2\nproperty int x\nend_header\n";
  const std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty list uchar int i\n"
      "end_header\n";
  const std::pair<std::string, const char*> cases[] = {
      {"plyx\n", "not a PLY file"},
      {"ply\nelement vertex 1\nend_header\n", "no format line"},
      {"ply\nformat ascii 2\nformat\nend_header\n", "line 3: unsupported PLY format"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n", "line 3: property before"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n1\n",
       "line 4: unknown PLY type 'half'"},
      {"ply\nformat ascii 1.0\nelement v -1\nend_header\n", "element count '-1' is not a count"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nend_header\n\n", "has no properties"},
      {ascii + "1\n2.5\n", "line 7: '2.5' is not a whole number"},
      {ascii + "1 2\n2\n", "line 6: 1 values more than declared"},
      {ascii + "1\n\n\n", "ends after 1 of the 2 vertices"},
      {ascii + "1\n2\n3\n", "line 8: more vertices than the 2 declared"},
      {"ply\nformat ascii 1.0\nelement vertex 9000000000\nproperty int x\nend_header\n1\n",
       "declares 9000000000 vertices but holds only 2 bytes"},
      {binary + std::string("\x02\x01\x00\x00\x00\x02\x00\x00\x00\x09", 10),
       "binary data ends inside element 'vertex'"},
      {binary + std::string("\x00\x00\x07", 3), "holds 1 bytes after its last vertex"},
  };
  for (const auto& [bytes, expected] : cases) {
    const std::string message = error_of(bytes);
    EXPECT_NE(message.find(expected), std::string::npos) << message << " | " << expected;
  }
}

}  // namespace
}  // namespace vantage
