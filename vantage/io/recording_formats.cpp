#include "vantage/io/recording_formats.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vantage/io/format_parsing.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Little-endian reads from a region of a file; `base` is the region's offset in the file (in
/// the decompressed chunk, for a chunk's records), for messages.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::uint64_t base, std::string_view where)
      : bytes_(bytes), base_(base), where_(where) {}
  bool done() const { return pos_ >= bytes_.size(); }
  std::uint64_t offset() const { return base_ + pos_; }
  template <class T>
  T scalar(std::string_view what) {
    const std::string_view raw = take(sizeof(T), what);
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));  // NOTE: both formats are little-endian.
    return value;
  }
  std::string_view take(std::uint64_t n, std::string_view what) {
    if (n > bytes_.size() - pos_) {
      throw FormatError(cat(what, " at byte ", offset(), where_, " runs past the end (", n,
                            " bytes, ", bytes_.size() - pos_, " left)"));
    }
    const std::string_view out = bytes_.substr(pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return out;
  }
  std::string_view where() const { return where_; }
  /// What is left, all of it.
  std::string_view rest() {
    const std::string_view out = bytes_.substr(pos_);
    pos_ = bytes_.size();
    return out;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::uint64_t base_ = 0;
  std::string_view where_;
};

// ---- ROS 1 bags ----

/// A bag record's header: `name=value` fields, each after its 4-byte length.
std::map<std::string_view, std::string_view> bag_fields(std::string_view header, std::uint64_t at) {
  std::map<std::string_view, std::string_view> fields;
  Cursor c(header, at, " of a record header");
  while (!c.done()) {
    const std::string_view field = c.take(c.scalar<std::uint32_t>("a field's length"), "a field");
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) {
      throw FormatError(cat("a record header field at byte ", at, " has no '='"));
    }
    fields[field.substr(0, eq)] = field.substr(eq + 1);
  }
  return fields;
}

std::string_view bag_field(const std::map<std::string_view, std::string_view>& fields,
                           std::string_view name, std::size_t size, std::uint64_t at) {
  const auto it = fields.find(name);
  if (it == fields.end() || (size > 0 && it->second.size() != size)) {
    throw FormatError(cat("the record at byte ", at, " has no ",
                          size > 0 ? cat(size, "-byte ") : "", "field '", name, "'"));
  }
  return it->second;
}

template <class T>
T bag_scalar(const std::map<std::string_view, std::string_view>& fields, std::string_view name,
             std::uint64_t at) {
  T value;
  std::memcpy(&value, bag_field(fields, name, sizeof(T), at).data(), sizeof(T));
  return value;
}

struct Connection {
  std::string_view topic, type;
};

void bag_records(Cursor c, std::map<std::uint32_t, Connection>& connections, bool in_chunk,
                 const MessageVisitor& visit) {
  while (!c.done()) {
    const std::uint64_t at = c.offset();
    const auto fields =
        bag_fields(c.take(c.scalar<std::uint32_t>("a header's length"), "a header"), at);
    const std::string_view data =
        c.take(c.scalar<std::uint32_t>("a data length"), "a record's data");
    const std::uint8_t op = static_cast<std::uint8_t>(bag_field(fields, "op", 1, at)[0]);
    if (op == 0x05) {  // chunk
      if (in_chunk) throw FormatError(cat("a chunk inside a chunk at byte ", at));
      const std::string_view compression = bag_field(fields, "compression", 0, at);
      if (compression != "none") {
        throw FormatError(cat("the chunk at byte ", at, " is compressed with '",
                              printable(compression, 20),
                              "'; Vantage reads uncompressed bags (rosbag decompress FILE.bag)"));
      }
      bag_records(Cursor(data, 0, cat(" of the chunk at byte ", at)), connections, true, visit);
    } else if (op == 0x07) {  // connection
      const auto conn = bag_scalar<std::uint32_t>(fields, "conn", at);
      const auto info = bag_fields(data, at);
      connections[conn] = {bag_field(fields, "topic", 0, at), bag_field(info, "type", 0, at)};
    } else if (op == 0x02) {  // message data
      const auto conn = bag_scalar<std::uint32_t>(fields, "conn", at);
      const auto time = bag_scalar<std::uint64_t>(fields, "time", at);
      const auto it = connections.find(conn);
      if (it == connections.end()) {
        throw FormatError(cat("the message at byte ", at, c.where(), " is of connection ", conn,
                              ", which no connection record before it defines"));
      }
      const double t =
          static_cast<double>(time & 0xffffffffu) + static_cast<double>(time >> 32) * 1e-9;
      visit({it->second.topic, it->second.type, RosEncoding::kRos1, t, data});
    }
    // NOTE: the bag header (3), index data (4) and chunk info (6) records index what is read
    // here in order anyway.
  }
}

// ---- MCAP ----

std::string_view mcap_string(Cursor& c, std::string_view what) {
  return c.take(c.scalar<std::uint32_t>(what), what);
}

/// Decompresses `data` with `step`, which turns some input into some output and says whether a
/// frame ended, into exactly `size` bytes. The output grows only as the decompressor fills it,
/// never past one byte beyond the claim (which shows that it lies), so that a chunk that claims
/// more than its data holds is refused before anything is allocated for the claim.
template <class Step>
std::string inflate(std::string_view data, std::uint64_t size, std::string_view name,
                    std::uint64_t at, Step step) {
  const std::uint64_t limit = size + 1;
  std::string out(static_cast<std::size_t>(std::min<std::uint64_t>(
                      limit, std::max<std::uint64_t>(std::uint64_t{1} << 16, 4 * data.size()))),
                  '\0');
  std::size_t read = 0, written = 0;
  bool ended = false;
  while (!(ended && read == data.size())) {
    if (written == out.size()) {
      if (out.size() >= limit) break;
      out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(limit, 2 * out.size())));
    }
    std::size_t in = data.size() - read, produced = out.size() - written;
    ended = step(data.data() + read, in, out.data() + written, produced);
    read += in;
    written += produced;
    if (in == 0 && produced == 0 && written < out.size()) break;  // the data is cut short
  }
  if (!ended || read != data.size() || written != size) {
    throw FormatError(
        cat("the ", name, " chunk at byte ", at, " does not decompress to its ", size, " bytes"));
  }
  out.resize(written);
  return out;
}

/// A compressed chunk's records, decompressed; the claimed size is checked against the memory
/// available, and the output never outgrows what the data decompresses to (`inflate`).
std::string decompress(std::string_view compression, std::string_view data, std::uint64_t size,
                       std::uint64_t at) {
  if (size > kMaxRecordingFileBytes || (available_memory() > 0 && size > available_memory())) {
    throw FormatError(cat("the chunk at byte ", at, " claims ", size,
                          " bytes uncompressed, more than the memory available"));
  }
  if (compression == "zstd") {
    const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> dctx(ZSTD_createDCtx(),
                                                                    &ZSTD_freeDCtx);
    if (!dctx) throw FormatError("zstd could not start");
    return inflate(
        data, size, "zstd", at, [&](const char* src, std::size_t& in, char* dst, std::size_t& out) {
          ZSTD_inBuffer input{src, in, 0};
          ZSTD_outBuffer output{dst, out, 0};
          const std::size_t r = ZSTD_decompressStream(dctx.get(), &output, &input);
          if (ZSTD_isError(r)) {
            throw FormatError(
                cat("the zstd chunk at byte ", at, " does not decompress: ", ZSTD_getErrorName(r)));
          }
          in = input.pos;
          out = output.pos;
          return r == 0;
        });
  }
  if (compression == "lz4") {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
      throw FormatError("lz4 could not start");
    }
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(
        raw, &LZ4F_freeDecompressionContext);
    return inflate(
        data, size, "lz4", at, [&](const char* src, std::size_t& in, char* dst, std::size_t& out) {
          const std::size_t r = LZ4F_decompress(dctx.get(), dst, &out, src, &in, nullptr);
          if (LZ4F_isError(r)) {
            throw FormatError(
                cat("the lz4 chunk at byte ", at, " does not decompress: ", LZ4F_getErrorName(r)));
          }
          return r == 0;
        });
  }
  throw FormatError(cat("the chunk at byte ", at, " is compressed with '",
                        printable(compression, 20), "' (Vantage reads zstd, lz4 and none)"));
}

struct McapState {
  std::map<std::uint16_t, std::string_view> schemas;  ///< id: name
  struct Channel {
    std::string_view topic, type;
    RosEncoding encoding = RosEncoding::kCdr;
    bool ros = false;
  };
  std::map<std::uint16_t, Channel> channels;
  std::vector<std::string> chunks;  ///< decompressed chunks, alive while their views are
};

void mcap_records(Cursor c, McapState& state, bool in_chunk, const MessageVisitor& visit) {
  while (!c.done()) {
    const std::uint64_t at = c.offset();
    const auto op = c.scalar<std::uint8_t>("a record's opcode");
    Cursor r(c.take(c.scalar<std::uint64_t>("a record's length"), "a record"), at + 9, c.where());
    if (op == 0x02) return;  // footer: the summary follows
    if (op == 0x03) {        // schema
      const auto id = r.scalar<std::uint16_t>("schema id");
      state.schemas[id] = mcap_string(r, "schema name");
    } else if (op == 0x04) {  // channel
      const auto id = r.scalar<std::uint16_t>("channel id");
      const auto schema = r.scalar<std::uint16_t>("channel schema id");
      McapState::Channel channel;
      channel.topic = mcap_string(r, "channel topic");
      const std::string_view encoding = mcap_string(r, "channel message encoding");
      channel.ros = encoding == "cdr" || encoding == "ros1";
      channel.encoding = encoding == "ros1" ? RosEncoding::kRos1 : RosEncoding::kCdr;
      const auto it = state.schemas.find(schema);
      if (schema != 0 && it == state.schemas.end()) {
        throw FormatError(cat("the channel at byte ", at, c.where(), " names schema ", schema,
                              ", which no schema record before it defines"));
      }
      channel.type = schema == 0 ? std::string_view() : it->second;
      state.channels[id] = channel;
    } else if (op == 0x05) {  // message
      const auto id = r.scalar<std::uint16_t>("message channel id");
      r.scalar<std::uint32_t>("message sequence");
      const auto log_time = r.scalar<std::uint64_t>("message log time");
      r.scalar<std::uint64_t>("message publish time");
      const auto it = state.channels.find(id);
      if (it == state.channels.end()) {
        throw FormatError(cat("the message at byte ", at, c.where(), " is on channel ", id,
                              ", which no channel record before it defines"));
      }
      if (it->second.ros) {
        visit({it->second.topic, it->second.type, it->second.encoding,
               static_cast<double>(log_time) * 1e-9, r.rest()});
      }
    } else if (op == 0x06) {  // chunk
      if (in_chunk) throw FormatError(cat("a chunk inside a chunk at byte ", at));
      r.scalar<std::uint64_t>("chunk start time");
      r.scalar<std::uint64_t>("chunk end time");
      const auto size = r.scalar<std::uint64_t>("chunk uncompressed size");
      r.scalar<std::uint32_t>("chunk crc");
      const std::string_view compression = mcap_string(r, "chunk compression");
      const std::string_view records =
          r.take(r.scalar<std::uint64_t>("chunk records length"), "chunk records");
      std::string_view body = records;
      if (!compression.empty()) {
        state.chunks.push_back(decompress(compression, records, size, at));
        body = state.chunks.back();
      }
      mcap_records(Cursor(body, 0, cat(" of the chunk at byte ", at)), state, true, visit);
      if (!compression.empty()) state.chunks.pop_back();
    }
  }
}

}  // namespace

void read_rosbag(std::string_view bytes, const MessageVisitor& visit) {
  static constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
  if (!bytes.starts_with(kMagic)) {
    throw FormatError(bytes.starts_with("#ROSBAG V")
                          ? cat("a ROS bag of another version (", printable(bytes.substr(0, 12)),
                                "); Vantage reads version 2.0")
                          : std::string("not a ROS 1 bag (no '#ROSBAG V2.0' at its start)"));
  }
  std::map<std::uint32_t, Connection> connections;
  bag_records(Cursor(bytes.substr(kMagic.size()), kMagic.size(), ""), connections, false, visit);
}

void read_mcap(std::string_view bytes, const MessageVisitor& visit) {
  static constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);
  if (!bytes.starts_with(kMagic)) {
    throw FormatError("not an MCAP file (no MCAP magic at its start)");
  }
  McapState state;
  mcap_records(Cursor(bytes.substr(kMagic.size()), kMagic.size(), ""), state, false, visit);
}

}  // namespace vantage
