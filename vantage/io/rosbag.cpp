// ROS 1 bags (format 2.0, wiki.ros.org/Bags/Format/2.0), read and checked (issues 38, 53).

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "vantage/io/detail/recording_records.hpp"
#include "vantage/io/recording_formats.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using detail::as_damage;
using detail::Cursor;
using detail::cut_short;
using detail::Unsupported;

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

/// What read_rosbag has found so far of a bag's chunks and its index.
struct BagReading {
  std::map<std::uint32_t, Connection> connections;
  std::vector<std::uint64_t> chunks;                                 // their offsets
  std::vector<std::map<std::uint32_t, std::uint32_t>> chunk_counts;  // messages per connection
  std::optional<std::uint64_t> index_at;  // the first connection or chunk info record outside
  std::uint32_t index_connections = 0, chunk_infos = 0;
};

/// A chunk (record `r`; `c` reads on after it): checked with the index data that follows it,
/// its messages returned to be given.
std::vector<BagMessage> read_chunk(const BagRecord& r, Cursor& c, BagReading& bag) {
  if (bag.index_at) {
    throw FormatError(
        cat("a chunk at byte ", r.at, " after the index that began at byte ", *bag.index_at));
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
  std::vector<BagMessage> messages = bag_chunk(r.data, r.at, bag.connections);
  bag.chunk_counts.push_back(check_bag_index(c, r.at, messages));
  bag.chunks.push_back(r.at);
  return messages;
}

/// A chunk info record of the index: it names the next chunk and counts its messages as it holds
/// them.
void check_chunk_info(const BagRecord& r, BagReading& bag) {
  if (!bag.index_at) bag.index_at = r.at;
  if (bag_scalar<std::uint32_t>(r.fields, "ver", r.at) != 1) {
    throw FormatError(cat("the chunk info at byte ", r.at, " is not of version 1"));
  }
  const auto pos = bag_scalar<std::uint64_t>(r.fields, "chunk_pos", r.at);
  const auto count = bag_scalar<std::uint32_t>(r.fields, "count", r.at);
  if (bag.chunk_infos >= bag.chunks.size() || bag.chunks[bag.chunk_infos] != pos) {
    throw FormatError(cat("the chunk info at byte ", r.at, " names a chunk at byte ", pos,
                          ", where the file holds none (or not in this order)"));
  }
  Cursor entries(r.data, 0, "");
  std::map<std::uint32_t, std::uint32_t> counts;
  for (std::uint32_t i = 0; i < count; ++i) {
    const auto conn = entries.scalar<std::uint32_t>("a connection");
    counts[conn] = entries.scalar<std::uint32_t>("a count");
  }
  if (!entries.done() || counts != bag.chunk_counts[bag.chunk_infos]) {
    throw FormatError(cat("the chunk info at byte ", r.at, " counts other messages than ",
                          "the chunk at byte ", pos, " holds"));
  }
  ++bag.chunk_infos;
}

/// A record at the top of the bag after its header; a chunk's messages are returned.
std::vector<BagMessage> read_top_record(const BagRecord& r, Cursor& c, BagReading& bag) {
  if (r.op == 0x05) return read_chunk(r, c, bag);
  if (r.op == 0x07) {  // connection, in the index
    if (!bag.index_at) bag.index_at = r.at;
    define_connection(r, bag.connections);
    ++bag.index_connections;
  } else if (r.op == 0x06) {
    check_chunk_info(r, bag);
  } else if (r.op == 0x04) {
    throw FormatError(cat("index data at byte ", r.at, " follows no chunk"));
  } else if (r.op == 0x03) {
    throw FormatError(cat("a second bag header at byte ", r.at));
  } else if (r.op == 0x02) {
    throw FormatError(cat("a message at byte ", r.at, " outside any chunk"));
  } else {
    throw FormatError(cat("a record of unknown op ", int{r.op}, " at byte ", r.at));
  }
  return {};
}

/// At the bag's end (byte `end`): the index where its header names it, with the chunks and
/// connections it counts.
void check_bag_end(const BagHeader& header, std::uint64_t end, const BagReading& bag) {
  if (header.index_pos == 0) {
    throw RecordingDamage(end, cat("the bag's header names no index (index_pos 0): its writer "
                                   "stopped before it closed the bag, which ends at byte ",
                                   end, " (rosbag reindex writes the index)"));
  }
  if (header.index_pos >= end) {
    throw RecordingDamage(end, cat("the file ends at byte ", end, ", before the index at byte ",
                                   header.index_pos, " its header names: cut short"));
  }
  if (!bag.index_at || *bag.index_at != header.index_pos) {
    throw RecordingDamage(
        header.index_pos,
        cat("the index its header names at byte ", header.index_pos,
            " is not where the index begins (",
            bag.index_at ? cat("byte ", *bag.index_at) : std::string("nowhere"), "): damaged"));
  }
  if (bag.chunks.size() != header.chunk_count || bag.chunk_infos != header.chunk_count ||
      bag.index_connections != header.conn_count) {
    throw RecordingDamage(
        *bag.index_at,
        cat("the bag's header counts ", header.chunk_count, " chunks and ", header.conn_count,
            " connections; the file holds ", bag.chunks.size(), " chunks, and its index ",
            bag.chunk_infos, " chunk infos and ", bag.index_connections, " connections: damaged"));
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
  BagReading bag;
  while (!c.done()) {
    const BagRecord r = top_bag_record(c);
    // NOTE: the messages are given outside as_damage: what the visitor throws is its own.
    std::vector<BagMessage> messages;
    as_damage(r.at, [&] { messages = read_top_record(r, c, bag); });
    for (const BagMessage& m : messages) {
      const Connection& conn = bag.connections.at(m.conn);
      visit({conn.topic, conn.type, RosEncoding::kRos1, m.time, m.data});
    }
  }
  check_bag_end(header, bytes.size(), bag);
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

}  // namespace vantage
