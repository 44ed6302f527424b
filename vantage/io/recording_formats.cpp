#include "vantage/io/recording_formats.hpp"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// What a reader refuses that is no damage: a compression or a version it does not read.
struct Unsupported : FormatError {
  using FormatError::FormatError;
};

/// Little-endian reads from a region of a file; `base` is the region's offset in the file (in
/// the decompressed chunk, for a chunk's records), for messages.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::uint64_t base, std::string_view where)
      : bytes_(bytes), base_(base), where_(where) {}
  bool done() const { return pos_ >= bytes_.size(); }
  std::uint64_t offset() const { return base_ + pos_; }
  std::uint64_t left() const { return bytes_.size() - pos_; }
  template <class T>
  T scalar(std::string_view what) {
    const std::string_view raw = take(sizeof(T), what);
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));  // NOTE: both formats are little-endian.
    return value;
  }
  /// The scalar `skip` bytes ahead, or nothing when the region ends before it; nothing is taken.
  template <class T>
  std::optional<T> peek(std::uint64_t skip) const {
    if (skip > left() || sizeof(T) > left() - skip) return std::nullopt;
    T value;
    std::memcpy(&value, bytes_.data() + pos_ + skip, sizeof(T));
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
  std::string where_;  // NOTE: owned: a Cursor is often made with a cat(...) temporary
};

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", value);
  return text;
}

std::uint32_t crc32_of(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

/// The damage of a record of the file that runs past its end: `claimed` bytes from `at`, `left`
/// there.
[[noreturn]] void cut_short(std::uint64_t at, std::uint64_t claimed, std::uint64_t left) {
  throw RecordingDamage(
      at, cat("the record at byte ", at, " runs past the file's end (it claims ", claimed,
              " bytes, ", left, " are there): the file is cut short or the length damaged"));
}

/// Runs `read` on the record at `at`; what it finds wrong, but for what Vantage does not read, is
/// damage there.
template <class Read>
void as_damage(std::uint64_t at, Read read) {
  try {
    read();
  } catch (const RecordingDamage&) {
    throw;
  } catch (const Unsupported&) {
    throw;
  } catch (const FormatError& e) {
    throw RecordingDamage(at, e.what());
  }
}

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

struct BagRecord {
  std::uint64_t at = 0;  ///< [byte] in the file, or in its chunk
  std::map<std::string_view, std::string_view> fields;
  std::string_view data;
  std::uint8_t op = 0;
};

/// The next record of `c`, inside a chunk; what runs past the chunk's end throws FormatError.
BagRecord bag_record(Cursor& c) {
  BagRecord r;
  r.at = c.offset();
  r.fields = bag_fields(c.take(c.scalar<std::uint32_t>("a header's length"), "a header"), r.at);
  r.data = c.take(c.scalar<std::uint32_t>("a data length"), "a record's data");
  r.op = static_cast<std::uint8_t>(bag_field(r.fields, "op", 1, r.at)[0]);
  return r;
}

/// The next record of the file; one that runs past the file's end is damage (a cut).
BagRecord top_bag_record(Cursor& c) {
  const std::uint64_t at = c.offset(), left = c.left();
  const auto header = c.peek<std::uint32_t>(0);
  if (!header) cut_short(at, 4, left);
  const auto data = c.peek<std::uint32_t>(4 + std::uint64_t{*header});
  if (!data) cut_short(at, 8 + std::uint64_t{*header}, left);
  const std::uint64_t size = 8 + std::uint64_t{*header} + *data;
  if (size > left) cut_short(at, size, left);
  BagRecord r;
  as_damage(at, [&] { r = bag_record(c); });
  return r;
}

struct Connection {
  std::string_view topic, type;
};

void define_connection(const BagRecord& r, std::map<std::uint32_t, Connection>& connections) {
  const auto conn = bag_scalar<std::uint32_t>(r.fields, "conn", r.at);
  const auto info = bag_fields(r.data, r.at);
  connections[conn] = {bag_field(r.fields, "topic", 0, r.at), bag_field(info, "type", 0, r.at)};
}

struct BagMessage {
  std::uint64_t offset = 0;  ///< [byte] in its chunk
  std::uint32_t conn = 0;
  double time = 0.0;  ///< [s]
  std::string_view data;
};

/// A chunk's records, parsed whole before any message is given: its connections (into
/// `connections`) and its messages.
std::vector<BagMessage> bag_chunk(std::string_view records, std::uint64_t at,
                                  std::map<std::uint32_t, Connection>& connections) {
  Cursor c(records, 0, cat(" of the chunk at byte ", at));
  std::vector<BagMessage> messages;
  while (!c.done()) {
    const BagRecord r = bag_record(c);
    if (r.op == 0x07) {
      define_connection(r, connections);
    } else if (r.op == 0x02) {
      const auto conn = bag_scalar<std::uint32_t>(r.fields, "conn", r.at);
      const auto time = bag_scalar<std::uint64_t>(r.fields, "time", r.at);
      if (!connections.contains(conn)) {
        throw FormatError(cat("the message at byte ", r.at, c.where(), " is of connection ", conn,
                              ", which no connection record before it defines"));
      }
      messages.push_back(
          {r.at, conn,
           static_cast<double>(time & 0xffffffffu) + static_cast<double>(time >> 32) * 1e-9,
           r.data});
    } else {
      throw FormatError(cat("a record of op ", int{r.op}, " at byte ", r.at, c.where(),
                            ", where a chunk holds connections and messages only"));
    }
  }
  return messages;
}

/// Checks the index data records that follow the chunk at `at` (taken from `c`) against its
/// messages: every message listed once, under its connection; throws RecordingDamage at the
/// chunk. Returns the chunk's messages per connection.
std::map<std::uint32_t, std::uint32_t> check_bag_index(Cursor& c, std::uint64_t at,
                                                       const std::vector<BagMessage>& messages) {
  std::map<std::uint64_t, std::uint32_t> conn_at;  // offset in the chunk: connection
  std::map<std::uint32_t, std::uint32_t> counts;
  for (const BagMessage& m : messages) {
    conn_at[m.offset] = m.conn;
    ++counts[m.conn];
  }
  std::set<std::uint64_t> listed;
  bool any = false;
  std::optional<RecordingDamage> cut;  // the record after the chunk's index data, cut short
  while (!c.done()) {
    Cursor ahead = c;
    BagRecord r;
    try {
      r = top_bag_record(ahead);
    } catch (const RecordingDamage& e) {
      // NOTE: said here only when it takes the chunk's index with it; else the chunk is whole,
      // and the cut is found after its messages are given.
      cut = e;
      break;
    }
    if (r.op != 0x04) break;
    c = ahead;
    any = true;
    as_damage(r.at, [&] {
      if (bag_scalar<std::uint32_t>(r.fields, "ver", r.at) != 1) {
        throw FormatError(cat("the index data at byte ", r.at, " is not of version 1"));
      }
      const auto conn = bag_scalar<std::uint32_t>(r.fields, "conn", r.at);
      const auto count = bag_scalar<std::uint32_t>(r.fields, "count", r.at);
      if (r.data.size() != 12 * std::uint64_t{count}) {
        throw FormatError(cat("the index data at byte ", r.at, " lists ", count, " messages in ",
                              r.data.size(), " bytes"));
      }
      Cursor entries(r.data, 0, "");
      for (std::uint32_t i = 0; i < count; ++i) {
        entries.scalar<std::uint64_t>("a time");
        const auto offset = entries.scalar<std::uint32_t>("an offset");
        const auto it = conn_at.find(offset);
        if (it == conn_at.end() || it->second != conn || !listed.insert(offset).second) {
          throw RecordingDamage(
              at, cat("the index data at byte ", r.at, " lists a message of connection ", conn,
                      " at byte ", offset, " of the chunk at byte ", at,
                      ", which the chunk does not hold there: damaged"));
        }
      }
    });
  }
  if (listed.size() != messages.size()) {
    if (cut) throw *cut;
    throw RecordingDamage(
        at, !any && c.done()
                ? cat("the file ends after the chunk at byte ", at,
                      ", before the index data that lists its messages: cut short")
                : cat("the chunk at byte ", at, " holds ", messages.size(),
                      " messages, and the index data after it lists ", listed.size(), ": damaged"));
  }
  return counts;
}

/// A bag's header record: where its index begins, and how many connections and chunks it has.
struct BagHeader {
  std::uint64_t index_pos = 0;
  std::uint32_t conn_count = 0, chunk_count = 0;
};

BagHeader bag_header(const BagRecord& r) {
  if (r.op != 0x03) {
    throw FormatError(cat("the first record, at byte ", r.at, ", is not the bag header (op ",
                          int{r.op}, ", not 3)"));
  }
  return {bag_scalar<std::uint64_t>(r.fields, "index_pos", r.at),
          bag_scalar<std::uint32_t>(r.fields, "conn_count", r.at),
          bag_scalar<std::uint32_t>(r.fields, "chunk_count", r.at)};
}

constexpr std::string_view kBagMagic = "#ROSBAG V2.0\n";

void check_bag_magic(std::string_view bytes) {
  if (!bytes.starts_with(kBagMagic)) {
    throw Unsupported(bytes.starts_with("#ROSBAG V")
                          ? cat("a ROS bag of another version (", printable(bytes.substr(0, 12)),
                                "); Vantage reads version 2.0")
                          : std::string("not a ROS 1 bag (no '#ROSBAG V2.0' at its start)"));
  }
}

// ---- MCAP ----

constexpr std::string_view kMcapMagic("\x89MCAP0\r\n", 8);

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
  throw Unsupported(cat("the chunk at byte ", at, " is compressed with '",
                        printable(compression, 20), "' (Vantage reads zstd, lz4 and none)"));
}

struct McapMessage {
  std::uint64_t offset = 0;  ///< [byte] in its chunk's records, or in the file
  std::uint16_t channel = 0;
  std::uint64_t log_time = 0;  ///< [ns]
  std::string_view data;
};

struct McapState {
  std::map<std::uint16_t, std::string> schemas;  ///< id: name
  struct Channel {
    std::string topic, type;
    RosEncoding encoding = RosEncoding::kCdr;
    bool ros = false;
  };
  std::map<std::uint16_t, Channel> channels;
  std::uint64_t messages = 0;                          ///< read, in all
  std::map<std::uint16_t, std::uint64_t> per_channel;  ///< read
  std::set<std::uint64_t> chunks;                      ///< the chunks' offsets in the file
  /// The last chunk's messages (offset in its records: channel), while its indexes follow it.
  std::optional<std::map<std::uint64_t, std::uint16_t>> last_chunk;
  std::uint64_t last_chunk_at = 0;
  std::optional<std::uint64_t> statistics_at;
  std::uint64_t statistics_messages = 0;
  std::uint32_t statistics_chunks = 0;
  std::map<std::uint16_t, std::uint64_t> statistics_per_channel;
};

/// Reads a schema or a channel record into `state`; throws FormatError.
void mcap_definition(std::uint8_t op, Cursor& r, std::uint64_t at, McapState& state) {
  if (op == 0x03) {
    const auto id = r.scalar<std::uint16_t>("schema id");
    state.schemas[id] = std::string(mcap_string(r, "schema name"));
    return;
  }
  const auto id = r.scalar<std::uint16_t>("channel id");
  const auto schema = r.scalar<std::uint16_t>("channel schema id");
  McapState::Channel channel;
  channel.topic = mcap_string(r, "channel topic");
  const std::string_view encoding = mcap_string(r, "channel message encoding");
  channel.ros = encoding == "cdr" || encoding == "ros1";
  channel.encoding = encoding == "ros1" ? RosEncoding::kRos1 : RosEncoding::kCdr;
  const auto it = state.schemas.find(schema);
  if (schema != 0 && it == state.schemas.end()) {
    throw FormatError(cat("the channel at byte ", at, r.where(), " names schema ", schema,
                          ", which no schema record before it defines"));
  }
  if (schema != 0) channel.type = it->second;
  state.channels[id] = std::move(channel);
}

McapMessage mcap_message(Cursor& r, std::uint64_t at, const McapState& state) {
  McapMessage m;
  m.offset = at;
  m.channel = r.scalar<std::uint16_t>("message channel id");
  r.scalar<std::uint32_t>("message sequence");
  m.log_time = r.scalar<std::uint64_t>("message log time");
  r.scalar<std::uint64_t>("message publish time");
  if (!state.channels.contains(m.channel)) {
    throw FormatError(cat("the message at byte ", at, r.where(), " is on channel ", m.channel,
                          ", which no channel record before it defines"));
  }
  m.data = r.rest();
  return m;
}

void give(const McapMessage& m, McapState& state, const MessageVisitor& visit) {
  ++state.messages;
  ++state.per_channel[m.channel];
  const McapState::Channel& channel = state.channels.at(m.channel);
  if (channel.ros) {
    visit({channel.topic, channel.type, channel.encoding, static_cast<double>(m.log_time) * 1e-9,
           m.data});
  }
}

/// A chunk (its record `r`, at `at`): checked (its size, its CRC) and parsed whole, its
/// messages returned to be given (views into the chunk, or into `inflated` when compressed).
std::vector<McapMessage> mcap_chunk(Cursor& r, std::uint64_t at, McapState& state,
                                    std::string& inflated) {
  r.scalar<std::uint64_t>("chunk start time");
  r.scalar<std::uint64_t>("chunk end time");
  const auto size = r.scalar<std::uint64_t>("chunk uncompressed size");
  const auto crc = r.scalar<std::uint32_t>("chunk crc");
  const std::string_view compression = mcap_string(r, "chunk compression");
  const std::string_view records =
      r.take(r.scalar<std::uint64_t>("chunk records length"), "chunk records");
  std::string_view body = records;
  if (compression.empty()) {
    if (size != records.size()) {
      throw FormatError(cat("the chunk at byte ", at, " claims ", size,
                            " bytes uncompressed, but holds ", records.size(), " uncompressed"));
    }
  } else {
    inflated = decompress(compression, records, size, at);
    body = inflated;
  }
  // NOTE: a CRC of 0 is none (mcap.dev/spec: "may be 0 to skip").
  if (crc != 0 && crc32_of(body) != crc) {
    throw FormatError(cat("the chunk at byte ", at, " fails its CRC (", hex(crc), " stored, ",
                          hex(crc32_of(body)), " of its records): a byte in it is damaged"));
  }
  Cursor c(body, 0, cat(" of the chunk at byte ", at));
  std::vector<McapMessage> messages;
  while (!c.done()) {
    const std::uint64_t offset = c.offset();
    const auto op = c.scalar<std::uint8_t>("a record's opcode");
    Cursor inner(c.take(c.scalar<std::uint64_t>("a record's length"), "a record"), offset + 9,
                 c.where());
    if (op == 0x03 || op == 0x04) {
      mcap_definition(op, inner, offset, state);
    } else if (op == 0x05) {
      messages.push_back(mcap_message(inner, offset, state));
    } else {
      throw FormatError(cat("a record of opcode ", int{op}, " at byte ", offset, c.where(),
                            ", where a chunk holds schemas, channels and messages only"));
    }
  }
  state.chunks.insert(at);
  state.last_chunk.emplace();
  state.last_chunk_at = at;
  for (const McapMessage& m : messages) (*state.last_chunk)[m.offset] = m.channel;
  return messages;
}

/// A message index record: every message it lists is one of the chunk before it, on its
/// channel, and it lists all of them.
void mcap_message_index(Cursor& r, std::uint64_t at, const McapState& state) {
  if (!state.last_chunk) {
    throw FormatError(cat("the message index at byte ", at, " follows no chunk"));
  }
  const auto channel = r.scalar<std::uint16_t>("message index channel id");
  Cursor entries(
      r.take(r.scalar<std::uint32_t>("message index records length"), "message index records"), 0,
      "");
  std::uint64_t listed = 0;
  while (!entries.done()) {
    entries.scalar<std::uint64_t>("a log time");
    const auto offset = entries.scalar<std::uint64_t>("an offset");
    const auto it = state.last_chunk->find(offset);
    if (it == state.last_chunk->end() || it->second != channel) {
      throw FormatError(cat("the message index at byte ", at, " lists a message on channel ",
                            channel, " at byte ", offset, " of the chunk at byte ",
                            state.last_chunk_at, ", which the chunk does not hold there"));
    }
    ++listed;
  }
  const auto held =
      static_cast<std::uint64_t>(std::count_if(state.last_chunk->begin(), state.last_chunk->end(),
                                               [&](const auto& m) { return m.second == channel; }));
  if (listed != held) {
    throw FormatError(cat("the message index at byte ", at, " lists ", listed,
                          " messages on channel ", channel, ", the chunk at byte ",
                          state.last_chunk_at, " holds ", held));
  }
}

void mcap_statistics(Cursor& r, std::uint64_t at, McapState& state) {
  state.statistics_at = at;
  state.statistics_messages = r.scalar<std::uint64_t>("message count");
  r.scalar<std::uint16_t>("schema count");
  r.scalar<std::uint32_t>("channel count");
  r.scalar<std::uint32_t>("attachment count");
  r.scalar<std::uint32_t>("metadata count");
  state.statistics_chunks = r.scalar<std::uint32_t>("chunk count");
  r.scalar<std::uint64_t>("message start time");
  r.scalar<std::uint64_t>("message end time");
  Cursor counts(
      r.take(r.scalar<std::uint32_t>("channel message counts length"), "channel message counts"), 0,
      "");
  state.statistics_per_channel.clear();
  while (!counts.done()) {
    const auto channel = counts.scalar<std::uint16_t>("a channel id");
    state.statistics_per_channel[channel] = counts.scalar<std::uint64_t>("a message count");
  }
}

/// The footer at `at` and what follows it: the closing magic, the summary's CRC, the statistics
/// against what was read.
void mcap_footer(std::string_view bytes, Cursor& r, std::uint64_t at, std::uint64_t end,
                 const McapState& state) {
  const auto summary_start = r.scalar<std::uint64_t>("footer summary start");
  r.scalar<std::uint64_t>("footer summary offset start");
  const auto summary_crc = r.scalar<std::uint32_t>("footer summary crc");
  const std::string_view after = bytes.substr(static_cast<std::size_t>(end));
  if (after != kMcapMagic) {
    throw RecordingDamage(
        at, kMcapMagic.starts_with(after)
                ? cat("the file ends ", after.size(), " bytes after its footer at byte ", at,
                      ", without its closing magic: cut short")
                : cat("the footer at byte ", at, " is followed by ", after.size(),
                      " bytes, not the closing magic alone: damaged"));
  }
  if (summary_start != 0) {
    if (summary_start < kMcapMagic.size() || summary_start > at) {
      throw RecordingDamage(at, cat("the footer at byte ", at, " puts the summary at byte ",
                                    summary_start, ", outside the file before it: damaged"));
    }
    // NOTE: the CRC covers the summary and the footer up to the CRC itself (mcap.dev/spec).
    const std::string_view summary = bytes.substr(
        static_cast<std::size_t>(summary_start), static_cast<std::size_t>(at + 25 - summary_start));
    if (summary_crc != 0 && crc32_of(summary) != summary_crc) {
      throw RecordingDamage(summary_start,
                            cat("the summary at byte ", summary_start,
                                " fails its CRC (the footer's at byte ", at, "): damaged"));
    }
  }
  if (state.statistics_at) {
    const std::uint64_t s = *state.statistics_at;
    if (state.statistics_messages != state.messages ||
        state.statistics_chunks != state.chunks.size()) {
      throw RecordingDamage(
          s, cat("the summary's statistics at byte ", s, " count ", state.statistics_messages,
                 " messages in ", state.statistics_chunks, " chunks, the file holds ",
                 state.messages, " in ", state.chunks.size(), ": damaged"));
    }
    for (const auto& [channel, count] : state.statistics_per_channel) {
      const auto it = state.per_channel.find(channel);
      const std::uint64_t read = it == state.per_channel.end() ? 0 : it->second;
      if (read != count) {
        throw RecordingDamage(
            s, cat("the summary's statistics at byte ", s, " count ", count,
                   " messages on channel ", channel, ", the file holds ", read, ": damaged"));
      }
    }
  }
}

}  // namespace

void read_rosbag(std::string_view bytes, const MessageVisitor& visit) {
  check_bag_magic(bytes);
  Cursor c(bytes.substr(kBagMagic.size()), kBagMagic.size(), "");
  if (c.done()) {
    throw RecordingDamage(kBagMagic.size(),
                          "the file ends at byte 13, right after its magic, without its header: "
                          "an empty bag, or one cut short");
  }
  const BagRecord first = top_bag_record(c);
  BagHeader header;
  as_damage(first.at, [&] { header = bag_header(first); });
  std::map<std::uint32_t, Connection> connections;
  std::vector<std::uint64_t> chunks;                                 // their offsets
  std::vector<std::map<std::uint32_t, std::uint32_t>> chunk_counts;  // messages per connection
  std::optional<std::uint64_t> index_at;  // the first connection or chunk info record outside
  std::uint32_t index_connections = 0, chunk_infos = 0;
  while (!c.done()) {
    const BagRecord r = top_bag_record(c);
    // NOTE: the messages are given outside as_damage: what the visitor throws is its own.
    std::vector<BagMessage> messages;
    as_damage(r.at, [&] {
      if (r.op == 0x05) {  // chunk
        if (index_at) {
          throw FormatError(
              cat("a chunk at byte ", r.at, " after the index that began at byte ", *index_at));
        }
        const std::string_view compression = bag_field(r.fields, "compression", 0, r.at);
        if (compression != "none") {
          throw Unsupported(cat("the chunk at byte ", r.at, " is compressed with '",
                                printable(compression, 20),
                                "'; Vantage reads uncompressed bags (rosbag decompress FILE.bag)"));
        }
        const auto size = bag_scalar<std::uint32_t>(r.fields, "size", r.at);
        if (size != r.data.size()) {
          throw FormatError(cat("the chunk at byte ", r.at, " claims ", size,
                                " bytes uncompressed, but holds ", r.data.size(), " uncompressed"));
        }
        messages = bag_chunk(r.data, r.at, connections);
        chunk_counts.push_back(check_bag_index(c, r.at, messages));
        chunks.push_back(r.at);
      } else if (r.op == 0x07) {  // connection, in the index
        if (!index_at) index_at = r.at;
        define_connection(r, connections);
        ++index_connections;
      } else if (r.op == 0x06) {  // chunk info
        if (!index_at) index_at = r.at;
        if (bag_scalar<std::uint32_t>(r.fields, "ver", r.at) != 1) {
          throw FormatError(cat("the chunk info at byte ", r.at, " is not of version 1"));
        }
        const auto pos = bag_scalar<std::uint64_t>(r.fields, "chunk_pos", r.at);
        const auto count = bag_scalar<std::uint32_t>(r.fields, "count", r.at);
        if (chunk_infos >= chunks.size() || chunks[chunk_infos] != pos) {
          throw FormatError(cat("the chunk info at byte ", r.at, " names a chunk at byte ", pos,
                                ", where the file holds none (or not in this order)"));
        }
        Cursor entries(r.data, 0, "");
        std::map<std::uint32_t, std::uint32_t> counts;
        for (std::uint32_t i = 0; i < count; ++i) {
          const auto conn = entries.scalar<std::uint32_t>("a connection");
          counts[conn] = entries.scalar<std::uint32_t>("a count");
        }
        if (!entries.done() || counts != chunk_counts[chunk_infos]) {
          throw FormatError(cat("the chunk info at byte ", r.at, " counts other messages than ",
                                "the chunk at byte ", pos, " holds"));
        }
        ++chunk_infos;
      } else if (r.op == 0x04) {
        throw FormatError(cat("index data at byte ", r.at, " follows no chunk"));
      } else if (r.op == 0x03) {
        throw FormatError(cat("a second bag header at byte ", r.at));
      } else if (r.op == 0x02) {
        throw FormatError(cat("a message at byte ", r.at, " outside any chunk"));
      } else {
        throw FormatError(cat("a record of unknown op ", int{r.op}, " at byte ", r.at));
      }
    });
    for (const BagMessage& m : messages) {
      const Connection& conn = connections.at(m.conn);
      visit({conn.topic, conn.type, RosEncoding::kRos1, m.time, m.data});
    }
  }
  const std::uint64_t end = bytes.size();
  if (header.index_pos == 0) {
    throw RecordingDamage(end, cat("the bag's header names no index (index_pos 0): its writer "
                                   "stopped before it closed the bag, which ends at byte ",
                                   end, " (rosbag reindex writes the index)"));
  }
  if (header.index_pos >= end) {
    throw RecordingDamage(end, cat("the file ends at byte ", end, ", before the index at byte ",
                                   header.index_pos, " its header names: cut short"));
  }
  if (!index_at || *index_at != header.index_pos) {
    throw RecordingDamage(
        header.index_pos,
        cat("the index its header names at byte ", header.index_pos,
            " is not where the index begins (",
            index_at ? cat("byte ", *index_at) : std::string("nowhere"), "): damaged"));
  }
  if (chunks.size() != header.chunk_count || chunk_infos != header.chunk_count ||
      index_connections != header.conn_count) {
    throw RecordingDamage(
        *index_at,
        cat("the bag's header counts ", header.chunk_count, " chunks and ", header.conn_count,
            " connections; the file holds ", chunks.size(), " chunks, and its index ", chunk_infos,
            " chunk infos and ", index_connections, " connections: damaged"));
  }
}

void read_mcap(std::string_view bytes, const MessageVisitor& visit) {
  if (!bytes.starts_with(kMcapMagic)) {
    throw Unsupported("not an MCAP file (no MCAP magic at its start)");
  }
  Cursor c(bytes.substr(kMcapMagic.size()), kMcapMagic.size(), "");
  if (c.done()) {
    throw RecordingDamage(kMcapMagic.size(),
                          "the file ends at byte 8, right after its opening magic: no header, no "
                          "message, no footer (an empty MCAP file, or one cut short)");
  }
  McapState state;
  while (!c.done()) {
    const std::uint64_t at = c.offset(), left = c.left();
    const auto op = c.peek<std::uint8_t>(0);
    const auto length = c.peek<std::uint64_t>(1);
    if (!length) cut_short(at, 9, left);
    if (*length > left - 9) cut_short(at, 9 + *length, left);
    c.take(9, "a record's opcode and length");
    Cursor r(c.take(*length, "a record"), at + 9, "");
    if (*op != 0x07) state.last_chunk.reset();
    // NOTE: the messages are given outside as_damage: what the visitor throws is its own.
    std::string inflated;
    std::vector<McapMessage> messages;
    if (*op == 0x02) {  // footer: the last record
      as_damage(at, [&] { mcap_footer(bytes, r, at, c.offset(), state); });
      return;
    }
    as_damage(at, [&] {
      if (*op == 0x03 || *op == 0x04) {
        mcap_definition(*op, r, at, state);
      } else if (*op == 0x05) {
        messages.push_back(mcap_message(r, at, state));
      } else if (*op == 0x06) {
        messages = mcap_chunk(r, at, state, inflated);
      } else if (*op == 0x07) {
        // NOTE: a message index follows its chunk, whose CRC held: damage here is the index's.
        mcap_message_index(r, at, state);
      } else if (*op == 0x0f) {  // data end
        const auto crc = r.scalar<std::uint32_t>("data section crc");
        if (crc != 0 && crc32_of(bytes.substr(0, static_cast<std::size_t>(at))) != crc) {
          throw FormatError(cat("the data section fails its CRC (the data end record's at byte ",
                                at,
                                "): a byte before it, outside every chunk whose own CRC "
                                "held, is damaged"));
        }
      } else if (*op == 0x0b) {
        mcap_statistics(r, at, state);
      } else if (*op == 0x08) {  // chunk index
        r.scalar<std::uint64_t>("message start time");
        r.scalar<std::uint64_t>("message end time");
        const auto chunk = r.scalar<std::uint64_t>("chunk start offset");
        if (!state.chunks.contains(chunk)) {
          throw FormatError(cat("the chunk index at byte ", at, " names a chunk at byte ", chunk,
                                ", where the file holds none"));
        }
      }
      // NOTE: the header (1), attachments (9, 10), metadata (12, 13) and summary offsets (14)
      // hold nothing a frame needs.
    });
    for (const McapMessage& m : messages) give(m, state, visit);
  }
  throw RecordingDamage(bytes.size(), cat("the file ends at byte ", bytes.size(),
                                          " without its footer and closing magic: cut short"));
}

RecordingIndex index_rosbag(std::string_view bytes) {
  RecordingIndex index;
  try {
    check_bag_magic(bytes);
    Cursor c(bytes.substr(kBagMagic.size()), kBagMagic.size(), "");
    const BagHeader header = bag_header(top_bag_record(c));
    if (header.index_pos < c.offset() || header.index_pos >= bytes.size()) return {};
    Cursor i(bytes.substr(static_cast<std::size_t>(header.index_pos)), header.index_pos, "");
    std::map<std::uint32_t, Connection> connections;
    std::map<std::uint32_t, std::uint64_t> counts;
    while (!i.done()) {
      const BagRecord r = top_bag_record(i);
      if (r.op == 0x07) {
        define_connection(r, connections);
      } else if (r.op == 0x06) {
        Cursor entries(r.data, 0, "");
        const auto count = bag_scalar<std::uint32_t>(r.fields, "count", r.at);
        for (std::uint32_t k = 0; k < count; ++k) {
          const auto conn = entries.scalar<std::uint32_t>("a connection");
          counts[conn] += entries.scalar<std::uint32_t>("a count");
        }
      }
    }
    for (const auto& [conn, count] : counts) {
      const auto it = connections.find(conn);
      if (it == connections.end()) return {};
      index[std::string(it->second.topic)] += count;
    }
  } catch (const FormatError&) {
    return {};
  }
  return index;
}

RecordingIndex index_mcap(std::string_view bytes) {
  // NOTE: the footer is the last record: 1 + 8 + 20 bytes before the closing magic.
  constexpr std::size_t kFooter = 29;
  RecordingIndex index;
  if (bytes.size() < 2 * kMcapMagic.size() + kFooter || !bytes.ends_with(kMcapMagic)) return {};
  try {
    const std::size_t footer = bytes.size() - kMcapMagic.size() - kFooter;
    Cursor f(bytes.substr(footer, kFooter), footer, "");
    if (f.scalar<std::uint8_t>("opcode") != 0x02 || f.scalar<std::uint64_t>("length") != 20) {
      return {};
    }
    const auto summary_start = f.scalar<std::uint64_t>("summary start");
    if (summary_start < kMcapMagic.size() || summary_start > footer) return {};
    Cursor s(bytes.substr(static_cast<std::size_t>(summary_start),
                          static_cast<std::size_t>(footer - summary_start)),
             summary_start, "");
    McapState state;
    while (!s.done()) {
      const std::uint64_t at = s.offset();
      const auto op = s.scalar<std::uint8_t>("opcode");
      Cursor r(s.take(s.scalar<std::uint64_t>("length"), "a record"), at + 9, "");
      if (op == 0x03 || op == 0x04) mcap_definition(op, r, at, state);
      if (op == 0x0b) mcap_statistics(r, at, state);
    }
    if (!state.statistics_at) return {};
    for (const auto& [channel, count] : state.statistics_per_channel) {
      const auto it = state.channels.find(channel);
      if (it == state.channels.end()) return {};
      index[it->second.topic] += count;
    }
  } catch (const FormatError&) {
    return {};
  }
  return index;
}

}  // namespace vantage
