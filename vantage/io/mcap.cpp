// MCAP (mcap.dev/spec), read and checked (issues 38, 53).

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "vantage/io/detail/mcap_decompress.hpp"
#include "vantage/io/detail/recording_records.hpp"
#include "vantage/io/recording_formats.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using detail::as_damage;
using detail::Cursor;
using detail::cut_short;
using detail::Unsupported;

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%08x", value);
  return text;
}

std::uint32_t crc32_of(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

constexpr std::string_view kMcapMagic("\x89MCAP0\r\n", 8);

std::string_view mcap_string(Cursor& c, std::string_view what) {
  return c.take(c.scalar<std::uint32_t>(what), what);
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
    inflated = detail::decompress_chunk(compression, records, size, at);
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
