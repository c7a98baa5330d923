// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Decoding serialized ROS messages of any type from their definition
/// (message_definition.hpp), in both wire formats recordings hold:
///
/// - ROS 1: little-endian, packed (no alignment), strings and sequences with a
///   uint32 length prefix, `time`/`duration` as two 32-bit integers.
/// - CDR (ROS 2, XCDR1): a 4-byte encapsulation header whose second byte gives
///   the byte order (0 big-, 1 little-endian); every primitive aligned to its
///   size (at most 8) relative to the end of that header; strings carry their
///   terminating NUL in the length.
///
/// The result is a flat list of leaves named by path ("header.stamp.sec",
/// "fields.2.name"). Arrays of primitives (a PointCloud2's `data`) and arrays
/// of fixed-size structures (a CustomMsg's `points`) stay on the wire and are
/// read in place: a message costs O(number of fields), not O(points).

#include <streamclust/io/byte_cursor.hpp>
#include <streamclust/io/ros/message_definition.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io::ros {

/// Wire formats of serialized messages.
enum class Encoding { ros1, cdr };

/// A primitive value or primitive array on the wire.
struct Leaf {
  std::string path;
  Primitive primitive = Primitive::uint8;
  bool is_array = false;
  std::size_t count = 1;    ///< elements (1 for a scalar)
  std::size_t offset = 0;   ///< of the first element in the payload [bytes]
  std::string text;         ///< the value of a string scalar
};

/// Where the leaves of a fixed-size structure lie, for one alignment phase.
struct ElementLayout {
  std::vector<std::size_t> offsets;  ///< per leaf of StructArray::leaves, from the element's start [bytes]
  std::size_t size = 0;              ///< bytes up to the element's last byte
};

/// An array of fixed-size structures, read in place.
struct StructArray {
  std::string path;
  std::size_t count = 0;
  std::size_t offset = 0;  ///< of the first element in the payload [bytes]
  /// The element's primitive leaves in order: path inside the element and type
  /// (fixed arrays inside the element are flattened as "name.0", "name.1", ...).
  std::vector<std::pair<std::string, Primitive>> leaves;
  /// Layout per start phase (offset from the alignment origin modulo 8).
  std::array<ElementLayout, 8> layouts;
  std::size_t first_alignment = 1;  ///< alignment of the element's first leaf [bytes]
  std::size_t origin = 0;           ///< the message's alignment origin [bytes]

  /// Calls f(element_offset, layout) for every element in order. O(count).
  template <class F>
  void for_each(F&& f) const {
    std::size_t pos = offset;
    for (std::size_t k = 0; k < count; ++k) {
      pos = origin + (pos - origin + first_alignment - 1) / first_alignment * first_alignment;
      const ElementLayout& l = layouts[(pos - origin) % 8];
      f(pos, l);
      pos += l.size;
    }
  }

  /// Index of the leaf named `name`, or npos.
  std::size_t leaf(std::string_view name) const noexcept {
    for (std::size_t i = 0; i < leaves.size(); ++i)
      if (leaves[i].first == name) return i;
    return npos;
  }
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
};

/// A decoded message: the payload, its byte order and its leaves.
/// Cheap to reuse across messages (clear() keeps capacity). Not thread-safe.
class DecodedMessage {
 public:
  const std::uint8_t* payload = nullptr;
  std::size_t size = 0;
  Encoding encoding = Encoding::ros1;
  bool big_endian = false;
  std::size_t origin = 0;  ///< CDR alignment origin (4), ROS 1: 0
  std::vector<Leaf> leaves;
  std::vector<StructArray> arrays;

  void clear() {
    leaves.clear();
    arrays.clear();
  }
  const Leaf* find(std::string_view path) const noexcept {
    for (const Leaf& l : leaves)
      if (l.path == path) return &l;
    return nullptr;
  }
  const StructArray* find_array(std::string_view path) const noexcept {
    for (const StructArray& a : arrays)
      if (a.path == path) return &a;
    return nullptr;
  }

  /// The integer value of the scalar leaf at payload offset `offset` (time and
  /// duration: seconds part). Floats are truncated.
  std::int64_t integer(Primitive p, std::size_t offset) const noexcept {
    switch (p) {
      case Primitive::boolean: case Primitive::uint8: return payload[offset];
      case Primitive::int8: return static_cast<std::int8_t>(payload[offset]);
      case Primitive::int16: return static_cast<std::int16_t>(load<std::uint16_t>(offset));
      case Primitive::uint16: return load<std::uint16_t>(offset);
      case Primitive::int32: case Primitive::duration: return static_cast<std::int32_t>(load<std::uint32_t>(offset));
      case Primitive::uint32: case Primitive::time: return load<std::uint32_t>(offset);
      case Primitive::int64: return static_cast<std::int64_t>(load<std::uint64_t>(offset));
      case Primitive::uint64: {
        const std::uint64_t v = load<std::uint64_t>(offset);
        return v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                   ? std::numeric_limits<std::int64_t>::max()
                   : static_cast<std::int64_t>(v);
      }
      case Primitive::float32: return static_cast<std::int64_t>(real(p, offset));
      case Primitive::float64: return static_cast<std::int64_t>(real(p, offset));
      case Primitive::string: return 0;
    }
    return 0;
  }
  /// The unsigned 64-bit value of an integer leaf (exact for uint64).
  std::uint64_t unsigned64(Primitive p, std::size_t offset) const noexcept {
    if (p == Primitive::uint64) return load<std::uint64_t>(offset);
    const std::int64_t v = integer(p, offset);
    return v < 0 ? 0 : static_cast<std::uint64_t>(v);
  }
  /// The value as a double.
  double real(Primitive p, std::size_t offset) const noexcept {
    if (p == Primitive::float32) {
      const std::uint32_t u = load<std::uint32_t>(offset);
      float f;
      std::memcpy(&f, &u, 4);
      return f;
    }
    if (p == Primitive::float64) {
      const std::uint64_t u = load<std::uint64_t>(offset);
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
    if (p == Primitive::uint64) return static_cast<double>(load<std::uint64_t>(offset));
    return static_cast<double>(integer(p, offset));
  }

  /// The unsigned value at `offset` in the message's byte order.
  template <class U>
  U load(std::size_t offset) const noexcept {
    U u = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) {
      const std::size_t shift = big_endian ? 8 * (sizeof(U) - 1 - i) : 8 * i;
      u = static_cast<U>(u | (static_cast<U>(payload[offset + i]) << shift));
    }
    return u;
  }
};

/// Decodes messages of one type. Construct once per topic; decode() per
/// message. Throws InputError (through the ByteCursor's origin) when a
/// message is shorter than its type needs or has bytes left over, a CDR
/// header is not plain CDR, or a count cannot fit the message. O(leaves) per
/// message. Not thread-safe.
class MessageDecoder {
 public:
  MessageDecoder(const MessageDefinitions& definitions, Encoding encoding)
      : definitions_(&definitions), encoding_(encoding) {}

  /// Decodes the `size` bytes at `payload` into `out` (which refers to them).
  void decode(const std::uint8_t* payload, std::size_t size, const detail::BufferOrigin& origin, DecodedMessage& out) {
    out.clear();
    out.payload = payload;
    out.size = size;
    out.encoding = encoding_;
    detail::ByteCursor c(payload, size, origin);
    if (encoding_ == Encoding::cdr) {
      const std::uint8_t* h = c.bytes(4, "CDR encapsulation header");
      if (h[0] != 0 || h[1] > 1) {
        c.fail_at(0, "CDR encapsulation " + hex(h[0]) + " " + hex(h[1]) +
                         ": expected plain CDR (00 00 big-endian or 00 01 little-endian)");
      }
      out.big_endian = h[1] == 0;
      out.origin = 4;
    } else {
      out.big_endian = false;
      out.origin = 0;
    }
    big_endian_ = out.big_endian;
    origin_ = out.origin;
    walk(definitions_->main(), std::string(), c, out);
    if (!c.at_end()) {
      c.fail("message of type " + definitions_->main().name + " has " + std::to_string(c.remaining()) +
             " bytes left after its last field: the definition does not match the data");
    }
  }

 private:
  static std::string hex(std::uint8_t v) {
    static const char* digits = "0123456789abcdef";
    return std::string{digits[v >> 4], digits[v & 15]};
  }

  std::size_t alignment(Primitive p) const noexcept {
    if (encoding_ == Encoding::ros1) return 1;
    if (p == Primitive::string) return 4;
    const std::size_t s = primitive_size(p);
    return s == 0 ? 1 : (s > 8 ? 8 : s);
  }

  void align(detail::ByteCursor& c, std::size_t a) const {
    if (a <= 1) return;
    const std::size_t rel = c.position() - origin_;
    const std::size_t pad = (a - rel % a) % a;
    c.skip(pad, "alignment padding");
  }

  std::uint32_t count(detail::ByteCursor& c) const {
    if (encoding_ == Encoding::cdr) align(c, 4);
    const std::uint8_t* p = c.bytes(4, "sequence length");
    std::uint32_t n = 0;
    for (std::size_t i = 0; i < 4; ++i) n |= static_cast<std::uint32_t>(p[i]) << (big_endian_ ? 8 * (3 - i) : 8 * i);
    return n;
  }

  void primitive(detail::ByteCursor& c, Primitive p, const std::string& path, DecodedMessage& out) const {
    Leaf leaf;
    leaf.path = path;
    leaf.primitive = p;
    if (p == Primitive::string) {
      const std::uint32_t n = count(c);
      const std::string what = "string " + path;
      const std::uint8_t* s = c.bytes(n, what.c_str());
      std::size_t len = n;
      if (encoding_ == Encoding::cdr && len > 0 && s[len - 1] == 0) --len;  // the terminating NUL
      leaf.text.assign(reinterpret_cast<const char*>(s), len);
    } else {
      align(c, alignment(p));
      leaf.offset = c.position();
      c.skip(primitive_size(p), path.c_str());
    }
    out.leaves.push_back(std::move(leaf));
  }

  /// Whether `t` has a size independent of its content (no strings, no sequences).
  bool fixed_size(const TypeDefinition& t, std::size_t depth = 0) const {
    if (depth > 32) return false;
    for (const FieldDefinition& f : t.fields) {
      if (f.array == FieldDefinition::Array::sequence) return false;
      if (f.primitive ? *f.primitive == Primitive::string : !fixed_size(definitions_->type(f.type_name), depth + 1))
        return false;
    }
    return true;
  }

  void flatten(const TypeDefinition& t, const std::string& prefix, StructArray& a) const {
    for (const FieldDefinition& f : t.fields) {
      const std::size_t n = f.array == FieldDefinition::Array::fixed ? f.fixed_length : 1;
      for (std::size_t k = 0; k < n; ++k) {
        const std::string name =
            prefix + f.name + (f.array == FieldDefinition::Array::fixed ? "." + std::to_string(k) : std::string());
        if (f.primitive) {
          if (*f.primitive == Primitive::time || *f.primitive == Primitive::duration) {
            a.leaves.emplace_back(name + ".sec", *f.primitive == Primitive::time ? Primitive::uint32 : Primitive::int32);
            a.leaves.emplace_back(name + ".nsec", *f.primitive == Primitive::time ? Primitive::uint32 : Primitive::int32);
          } else {
            a.leaves.emplace_back(name, *f.primitive);
          }
        } else {
          flatten(definitions_->type(f.type_name), name + ".", a);
        }
      }
    }
  }

  ElementLayout layout_for(const StructArray& a, std::size_t phase) const {
    ElementLayout l;
    std::size_t pos = phase;
    for (const auto& leaf : a.leaves) {
      const std::size_t al = alignment(leaf.second);
      pos = (pos + al - 1) / al * al;
      l.offsets.push_back(pos - phase);
      pos += primitive_size(leaf.second);
    }
    l.size = pos - phase;
    return l;
  }

  /// Primitive leaves of one `t` with its fixed arrays unrolled, saturating
  /// above `limit` (nested fixed arrays multiply: 1e8 x 1e8 stays cheap).
  std::size_t leaf_count(const TypeDefinition& t, std::size_t limit, std::size_t depth = 0) const {
    std::size_t total = 0;
    for (const FieldDefinition& f : t.fields) {
      const std::size_t n = f.array == FieldDefinition::Array::fixed ? f.fixed_length : 1;
      const bool pair = f.primitive && (*f.primitive == Primitive::time || *f.primitive == Primitive::duration);
      const std::size_t each = f.primitive ? (pair ? 2 : 1) : depth > 32 ? limit + 1 : leaf_count(definitions_->type(f.type_name), limit, depth + 1);
      if (each != 0 && n > (limit + 1 - total) / each) return limit + 1;
      total += n * each;
    }
    return total;
  }

  /// An element type with more primitive fields than this is refused: point
  /// types have a handful, and each message unrolls its element's layout.
  static constexpr std::size_t kMaxElementLeaves = 4096;

  void struct_array(detail::ByteCursor& c, const TypeDefinition& t, std::size_t n, const std::string& path,
                    DecodedMessage& out) const {
    if (leaf_count(t, kMaxElementLeaves) > kMaxElementLeaves) {
      c.fail("array " + path + ": an element of " + t.name + " has more than " + std::to_string(kMaxElementLeaves) +
             " primitive fields (fixed arrays unrolled): not a point type");
    }
    StructArray a;
    a.path = path;
    a.count = n;
    flatten(t, std::string(), a);
    for (std::size_t phase = 0; phase < (encoding_ == Encoding::cdr ? 8u : 1u); ++phase) a.layouts[phase] = layout_for(a, phase);
    if (encoding_ == Encoding::ros1) {
      for (std::size_t phase = 1; phase < 8; ++phase) a.layouts[phase] = a.layouts[0];
    }
    // Elements of zero size cannot be told apart from a lying count.
    if (n > 0 && a.layouts[0].size == 0 && n > 1000000) c.fail("array " + path + " of " + std::to_string(n) + " empty elements");
    if (n > 0 && a.layouts[0].size > 0 && n > c.remaining()) {
      c.fail("array " + path + " of " + std::to_string(n) + " elements of " + std::to_string(a.layouts[0].size) +
             " bytes: the message has " + std::to_string(c.remaining()) + " bytes left");
    }
    a.first_alignment = a.leaves.empty() ? 1 : alignment(a.leaves.front().second);
    a.origin = origin_;
    a.offset = c.position();
    const std::string what = "element of " + path;
    for (std::size_t k = 0; k < n; ++k) {
      align(c, a.first_alignment);
      const std::size_t phase = (c.position() - origin_) % 8;
      c.skip(a.layouts[phase].size, what.c_str());
    }
    out.arrays.push_back(std::move(a));
  }

  void field(detail::ByteCursor& c, const FieldDefinition& f, const std::string& path, DecodedMessage& out,
             std::size_t depth) {
    if (f.array == FieldDefinition::Array::none) {
      if (f.primitive) {
        scalar(c, *f.primitive, path, out);
      } else {
        walk(definitions_->type(f.type_name), path + ".", c, out, depth + 1);
      }
      return;
    }
    const std::size_t n = f.array == FieldDefinition::Array::fixed ? f.fixed_length : count(c);
    if (f.primitive && *f.primitive != Primitive::string && *f.primitive != Primitive::time &&
        *f.primitive != Primitive::duration) {
      Leaf leaf;
      leaf.path = path;
      leaf.primitive = *f.primitive;
      leaf.is_array = true;
      leaf.count = n;
      const std::size_t s = primitive_size(*f.primitive);
      if (n > 0) align(c, alignment(*f.primitive));
      leaf.offset = c.position();
      if (n > c.remaining() / s) {
        c.fail("array " + path + " of " + std::to_string(n) + " x " + std::to_string(s) + " bytes: the message has " +
               std::to_string(c.remaining()) + " bytes left");
      }
      c.skip(n * s, path.c_str());
      out.leaves.push_back(std::move(leaf));
      return;
    }
    if (!f.primitive && fixed_size(definitions_->type(f.type_name))) {
      struct_array(c, definitions_->type(f.type_name), n, path, out);
      return;
    }
    // Strings, times or variable-size structures: element by element (each
    // takes at least one byte's worth of the message, or the count lies).
    if (n > c.remaining()) {
      c.fail("array " + path + " of " + std::to_string(n) + " elements: the message has " +
             std::to_string(c.remaining()) + " bytes left");
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::string element = path + "." + std::to_string(k);
      if (f.primitive) {
        scalar(c, *f.primitive, element, out);
      } else {
        walk(definitions_->type(f.type_name), element + ".", c, out, depth + 1);
      }
    }
  }

  void scalar(detail::ByteCursor& c, Primitive p, const std::string& path, DecodedMessage& out) const {
    if (p == Primitive::time || p == Primitive::duration) {
      const Primitive part = p == Primitive::time ? Primitive::uint32 : Primitive::int32;
      primitive(c, part, path + ".sec", out);
      primitive(c, part, path + ".nsec", out);
      return;
    }
    primitive(c, p, path, out);
  }

  void walk(const TypeDefinition& t, const std::string& prefix, detail::ByteCursor& c, DecodedMessage& out,
            std::size_t depth = 0) {
    for (const FieldDefinition& f : t.fields) field(c, f, prefix + f.name, out, depth);
  }

  const MessageDefinitions* definitions_;
  Encoding encoding_;
  bool big_endian_ = false;
  std::size_t origin_ = 0;
};

}  // namespace streamclust::io::ros
