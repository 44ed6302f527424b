#include "vantage/io/ply.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vantage/util/text.hpp"

namespace vantage {
namespace {

constexpr std::string_view kFormatNames[] = {"ascii", "binary_little_endian", "binary_big_endian"};

struct NamedType {
  std::string_view name, alias;
  ScalarType type;
};
constexpr NamedType kTypes[] = {
    {"char", "int8", {'I', 1}},     {"uchar", "uint8", {'U', 1}},    {"short", "int16", {'I', 2}},
    {"ushort", "uint16", {'U', 2}}, {"int", "int32", {'I', 4}},      {"uint", "uint32", {'U', 4}},
    {"float", "float32", {'F', 4}}, {"double", "float64", {'F', 8}},
};

std::optional<ScalarType> type_of(std::string_view name) {
  for (const NamedType& t : kTypes) {
    if (name == t.name || name == t.alias) return t.type;
  }
  return std::nullopt;
}

std::string_view name_of(const ScalarType& type) {
  for (const NamedType& t : kTypes) {
    if (t.type.kind == type.kind && t.type.size == type.size) return t.name;
  }
  throw std::invalid_argument(cat("PLY has no scalar type ", type.kind, type.size));
}

/// How messages call the instances of an element: "vertices", "faces", "'camera' items".
std::string instances(const PlyElement& e) {
  if (e.name == "vertex") return "vertices";
  if (e.name == "face") return "faces";
  return cat("'", e.name, "' items");
}

PlyProperty parse_property(const std::vector<std::string_view>& t, int n) {
  if (t.size() == 5 && t[1] == "list") {
    const auto count_type = type_of(t[2]);
    const auto item_type = type_of(t[3]);
    if (!count_type || !item_type || !count_type->integral()) {
      throw FormatError(cat("line ", n, ": unsupported list types '", printable(t[2], 40), " ",
                            printable(t[3], 40), "'"));
    }
    return {std::string(t[4]), *item_type, true, *count_type};
  }
  if (t.size() == 3) {
    const auto type = type_of(t[1]);
    if (!type) throw FormatError(cat("line ", n, ": unknown PLY type '", printable(t[1], 40), "'"));
    return {std::string(t[2]), *type, false, {}};
  }
  throw FormatError(cat("line ", n, ": malformed property line"));
}

}  // namespace

std::optional<std::size_t> PlyElement::find(std::string_view property, bool list) const {
  for (std::size_t k = 0; k < properties.size(); ++k) {
    if (properties[k].name == property && properties[k].is_list == list) return k;
  }
  return std::nullopt;
}

PlyReader::PlyReader(std::string_view bytes) : bytes_(bytes) {
  Lines lines(bytes);
  if (const auto first = lines.next(); !first || *first != "ply") {
    throw FormatError("not a PLY file: the first line is not 'ply'");
  }
  bool have_format = false;
  for (;;) {
    const auto line = lines.next();
    if (!line) throw FormatError("the PLY header has no end_header line");
    const std::vector<std::string_view> t = split(*line);
    const int n = lines.number();
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") break;
    if (t[0] == "format") {
      const auto* it = std::find(std::begin(kFormatNames), std::end(kFormatNames),
                                 t.size() == 3 ? t[1] : std::string_view());
      if (it == std::end(kFormatNames)) {
        throw FormatError(cat("line ", n, ": unsupported PLY format '", printable(*line, 60), "'"));
      }
      format_ = static_cast<PlyFormat>(it - std::begin(kFormatNames));
      have_format = true;
    } else if (t[0] == "element") {
      if (t.size() != 3) throw FormatError(cat("line ", n, ": expected 'element <name> <count>'"));
      elements_.push_back({std::string(t[1]), count_at(t[2], n, "element count"), {}});
    } else if (t[0] == "property") {
      if (elements_.empty()) throw FormatError(cat("line ", n, ": property before any element"));
      elements_.back().properties.push_back(parse_property(t, n));
    } else {
      throw FormatError(
          cat("line ", n, ": unknown PLY header keyword '", printable(t[0], 40), "'"));
    }
  }
  if (!have_format) throw FormatError("the PLY header has no format line");
  body_ = lines.position();
  header_lines_ = lines.number();
  check_counts();
}

void PlyReader::check_counts() const {
  // NOTE: a lying count must fail here, before a caller reserves memory for it.
  std::uint64_t available = bytes_.size() - body_;
  if (format_ == PlyFormat::kAscii) available = (available + 1) / 2;  // a value and a newline
  for (const PlyElement& e : elements_) {
    if (e.count == 0) continue;
    if (e.properties.empty()) throw FormatError(cat("element '", e.name, "' has no properties"));
    std::uint64_t each = 1;  // ASCII: one line
    if (format_ != PlyFormat::kAscii) {
      each = 0;
      for (const PlyProperty& p : e.properties) {
        each += static_cast<std::uint64_t>(p.is_list ? p.count_type.size : p.type.size);
      }
    }
    if (e.count > available / each) {
      throw FormatError(cat("declares ", e.count, " ", instances(e), " but holds only ",
                            bytes_.size() - body_, " bytes of data"));
    }
    available -= e.count * each;
  }
}

std::optional<std::size_t> PlyReader::find(std::string_view name) const {
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    if (elements_[e].name == name) return e;
  }
  return std::nullopt;
}

void PlyReader::read(std::size_t last, const Visitor& visit) const {
  if (last >= elements_.size()) {
    throw std::invalid_argument(cat("PlyReader::read: no element ", last));
  }
  if (format_ == PlyFormat::kAscii) {
    read_ascii(last, visit);
  } else {
    read_binary(last, visit);
  }
}

void PlyReader::read_ascii(std::size_t last, const Visitor& visit) const {
  Lines lines(bytes_, body_, header_lines_);
  PlyRecord record;
  for (std::size_t e = 0; e <= last; ++e) {
    const PlyElement& element = elements_[e];
    for (std::uint64_t i = 0; i < element.count; ++i) {
      const auto line = lines.next_nonblank();
      if (!line) {
        throw FormatError(cat("ends after ", i, " of the ", element.count, " ", instances(element),
                              " it declares"));
      }
      const std::vector<std::string_view> tokens = split(*line);
      const int n = lines.number();
      std::size_t t = 0;
      const auto value = [&](const ScalarType& type) {
        if (t >= tokens.size()) throw FormatError(cat("line ", n, ": too few values"));
        const double v = number_at(tokens[t], n);
        if (type.integral() && v != std::floor(v)) {
          throw FormatError(
              cat("line ", n, ": '", printable(tokens[t], 40), "' is not a whole number"));
        }
        ++t;
        return v;
      };
      record.values_.clear();
      record.begin_.clear();
      for (const PlyProperty& p : element.properties) {
        record.begin_.push_back(record.values_.size());
        if (!p.is_list) {
          record.values_.push_back(value(p.type));
          continue;
        }
        if (t >= tokens.size()) throw FormatError(cat("line ", n, ": too few values"));
        const std::uint64_t items = count_at(tokens[t++], n, "list length");
        if (items > tokens.size() - t) throw FormatError(cat("line ", n, ": too few values"));
        for (std::uint64_t j = 0; j < items; ++j) record.values_.push_back(value(p.type));
      }
      record.begin_.push_back(record.values_.size());
      if (t != tokens.size()) {
        throw FormatError(cat("line ", n, ": ", tokens.size() - t, " values more than declared"));
      }
      visit(e, i, record);
    }
  }
  if (last + 1 == elements_.size() && lines.next_nonblank()) {
    throw FormatError(cat("line ", lines.number(), ": more ", instances(elements_[last]),
                          " than the ", elements_[last].count, " declared"));
  }
}

void PlyReader::read_binary(std::size_t last, const Visitor& visit) const {
  const bool swap = format_ == PlyFormat::kBinaryBigEndian;
  const std::string_view body = bytes_.substr(body_);
  std::size_t at = 0;
  PlyRecord record;
  for (std::size_t e = 0; e <= last; ++e) {
    const PlyElement& element = elements_[e];
    const auto ends_inside = [&element] {
      return FormatError(cat("binary data ends inside element '", element.name, "'"));
    };
    const auto take = [&](std::size_t bytes) {
      if (body.size() - at < bytes) throw ends_inside();
      const char* p = body.data() + at;
      at += bytes;
      return p;
    };
    for (std::uint64_t i = 0; i < element.count; ++i) {
      record.values_.clear();
      record.begin_.clear();
      for (const PlyProperty& p : element.properties) {
        record.begin_.push_back(record.values_.size());
        const auto size = static_cast<std::size_t>(p.type.size);
        if (!p.is_list) {
          record.values_.push_back(decode_scalar(take(size), p.type, swap));
          continue;
        }
        const double items =
            decode_scalar(take(static_cast<std::size_t>(p.count_type.size)), p.count_type, swap);
        if (items < 0) {
          throw FormatError(cat("negative list length in element '", element.name, "'"));
        }
        if (items > static_cast<double>((body.size() - at) / size)) throw ends_inside();
        const char* item = take(static_cast<std::size_t>(items) * size);
        for (std::size_t j = 0; j < static_cast<std::size_t>(items); ++j, item += size) {
          record.values_.push_back(decode_scalar(item, p.type, swap));
        }
      }
      record.begin_.push_back(record.values_.size());
      visit(e, i, record);
    }
  }
  if (last + 1 == elements_.size() && at != body.size()) {
    throw FormatError(
        cat("holds ", body.size() - at, " bytes after its last ", elements_[last].name));
  }
}

std::string ply_header(PlyFormat format, const std::vector<std::string>& comments,
                       const std::vector<PlyElement>& elements) {
  std::string header =
      cat("ply\nformat ", kFormatNames[static_cast<std::size_t>(format)], " 1.0\n");
  for (const std::string& comment : comments) header += cat("comment ", comment, "\n");
  for (const PlyElement& e : elements) {
    header += cat("element ", e.name, " ", e.count, "\n");
    for (const PlyProperty& p : e.properties) {
      header += p.is_list ? cat("property list ", name_of(p.count_type), " ", name_of(p.type), " ",
                                p.name, "\n")
                          : cat("property ", name_of(p.type), " ", p.name, "\n");
    }
  }
  return header + "end_header\n";
}

}  // namespace vantage
