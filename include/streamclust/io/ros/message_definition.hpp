// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// ROS message definitions as recordings carry them: a ROS 1 bag's
/// connection `message_definition`, an MCAP schema of encoding `ros1msg` or
/// `ros2msg`, a rosbag2 `message_definitions` row. The text is the main
/// type's fields followed by every type it uses, each after a line of `=`
/// and a line `MSG: pkg/Type`:
///
///     std_msgs/Header header
///     uint64 timebase
///     CustomPoint[] points
///     ================================================================================
///     MSG: livox_ros_driver2/CustomPoint
///     uint32 offset_time
///     float32 x
///     ...
///
/// Parsing gives each type its ordered fields; constants (`uint8 FOO=1`),
/// comments and ROS 2 default values are skipped.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace streamclust::io::ros {

/// Primitive types of ROS messages (ROS 1 `time`/`duration` are two 32-bit
/// integers; `char` and `byte` are 8-bit).
enum class Primitive { boolean, int8, uint8, int16, uint16, int32, uint32, int64, uint64, float32, float64, string,
                       time, duration };

/// Size [bytes] of a primitive on the wire (0 for string).
inline std::size_t primitive_size(Primitive p) noexcept {
  switch (p) {
    case Primitive::boolean: case Primitive::int8: case Primitive::uint8: return 1;
    case Primitive::int16: case Primitive::uint16: return 2;
    case Primitive::int32: case Primitive::uint32: case Primitive::float32: return 4;
    case Primitive::int64: case Primitive::uint64: case Primitive::float64: case Primitive::time:
    case Primitive::duration: return 8;
    case Primitive::string: return 0;
  }
  return 0;
}

/// One field of a message type.
struct FieldDefinition {
  std::string name;
  /// The primitive type, or nothing for a message type (`type_name`).
  std::optional<Primitive> primitive;
  /// The message type's full name "pkg/Type" (for a primitive, its spelling).
  std::string type_name;
  enum class Array { none, fixed, sequence } array = Array::none;
  std::size_t fixed_length = 0;  ///< for Array::fixed
};

/// A message type: its fields in order.
struct TypeDefinition {
  std::string name;  ///< "pkg/Type"
  std::vector<FieldDefinition> fields;
};

/// The types of a definition text, looked up by "pkg/Type". Immutable after
/// parsing; thread-safe to share.
class MessageDefinitions {
 public:
  /// A type whose fields, with its nested fixed arrays of messages unrolled,
  /// number more than this is refused: decoding visits each of them per
  /// message, and a few nested `T[100000]` would make that unbounded.
  static constexpr std::size_t kMaxUnrolledFields = 65536;

  /// Parses `text` for the message type `main_type` ("pkg/Type" or ROS 2's
  /// "pkg/msg/Type"). Throws std::invalid_argument naming the line when the
  /// text is malformed, or naming the type when a used type is not defined in
  /// it, contains itself or unrolls to more than kMaxUnrolledFields fields.
  MessageDefinitions(std::string_view main_type, std::string_view text) : main_(normalize(main_type)) {
    std::string current = main_;
    types_[current].name = current;
    std::size_t line_no = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
      const std::size_t end = std::min(text.find('\n', pos), text.size());
      std::string_view line = text.substr(pos, end - pos);
      pos = end + 1;
      ++line_no;
      if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      line = trim(line);
      if (line.empty()) continue;
      if (line.find_first_not_of('=') == std::string_view::npos) continue;  // separator
      if (line.rfind("MSG:", 0) == 0) {
        current = normalize(trim(line.substr(4)));
        if (current.empty()) fail(line_no, "\"MSG:\" without a type name");
        if (types_.count(current) != 0 && !types_[current].fields.empty()) continue;  // repeated definition
        types_[current].name = current;
        continue;
      }
      parse_field(line, line_no, current);
    }
    resolve();
  }

  /// The main type.
  const TypeDefinition& main() const { return types_.at(main_); }
  /// The type named `name` ("pkg/Type"); throws std::out_of_range when absent.
  const TypeDefinition& type(const std::string& name) const { return types_.at(name); }

  /// "pkg/msg/Type" -> "pkg/Type"; other names unchanged.
  static std::string normalize(std::string_view name) {
    std::string s(name);
    if (const std::size_t at = s.find("/msg/"); at != std::string::npos) s.erase(at, 4);
    return s;
  }

 private:
  static std::string_view trim(std::string_view s) noexcept {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
  }

  [[noreturn]] static void fail(std::size_t line, const std::string& what) {
    throw std::invalid_argument("message definition line " + std::to_string(line) + ": " + what);
  }

  static std::optional<Primitive> primitive_of(std::string_view t) {
    static const std::map<std::string_view, Primitive> names = {
        {"bool", Primitive::boolean},   {"int8", Primitive::int8},       {"byte", Primitive::int8},
        {"char", Primitive::uint8},     {"uint8", Primitive::uint8},     {"int16", Primitive::int16},
        {"uint16", Primitive::uint16},  {"int32", Primitive::int32},     {"uint32", Primitive::uint32},
        {"int64", Primitive::int64},    {"uint64", Primitive::uint64},   {"float32", Primitive::float32},
        {"float64", Primitive::float64}, {"string", Primitive::string},  {"time", Primitive::time},
        {"duration", Primitive::duration}};
    if (t.rfind("string<=", 0) == 0) return Primitive::string;  // ROS 2 bounded string
    const auto it = names.find(t);
    if (it == names.end()) return std::nullopt;
    return it->second;
  }

  void parse_field(std::string_view line, std::size_t line_no, const std::string& owner) {
    const std::size_t space = line.find_first_of(" \t");
    if (space == std::string_view::npos) fail(line_no, "expected \"TYPE NAME\", found \"" + std::string(line) + "\"");
    std::string_view type = line.substr(0, space);
    std::string_view rest = trim(line.substr(space));
    const std::size_t name_end = rest.find_first_of(" \t=");
    const std::string_view name = rest.substr(0, name_end);
    if (name.empty()) fail(line_no, "field without a name");
    if (name_end != std::string_view::npos && trim(rest.substr(name_end)).rfind('=', 0) == 0) return;  // constant
    FieldDefinition f;
    f.name = std::string(name);
    if (const std::size_t bracket = type.find('['); bracket != std::string_view::npos) {
      if (type.back() != ']') fail(line_no, "malformed array type \"" + std::string(type) + "\"");
      const std::string_view inside = type.substr(bracket + 1, type.size() - bracket - 2);
      type = type.substr(0, bracket);
      if (inside.empty() || inside.rfind("<=", 0) == 0) {
        f.array = FieldDefinition::Array::sequence;  // T[] and ROS 2's bounded T[<=N]
      } else {
        std::size_t n = 0;
        for (const char c : inside) {
          if (c < '0' || c > '9' || n > 100000000) fail(line_no, "bad array length \"" + std::string(inside) + "\"");
          n = n * 10 + static_cast<std::size_t>(c - '0');
        }
        f.array = FieldDefinition::Array::fixed;
        f.fixed_length = n;
      }
    }
    f.primitive = primitive_of(type);
    if (f.primitive) {
      f.type_name = std::string(type);
    } else if (type == "Header") {
      f.type_name = "std_msgs/Header";
    } else if (type.find('/') == std::string_view::npos) {
      f.type_name = owner.substr(0, owner.find('/') + 1) + std::string(type);  // same package
    } else {
      f.type_name = normalize(type);
    }
    types_[owner].fields.push_back(std::move(f));
  }

  /// Checks that every message type used is defined, that no type contains
  /// itself and that none unrolls to more than kMaxUnrolledFields fields.
  /// O(types + fields).
  void resolve() const {
    std::map<std::string, int> state;              // 1 visiting, 2 done
    std::map<std::string, std::size_t> unrolled;   // of the done types, saturating
    for (const auto& entry : types_) visit(entry.first, state, unrolled);
  }

  /// Visits `name` after the types it uses; returns its unrolled field count
  /// (a primitive or a primitive array is one field, a message field one plus
  /// its own, times the length of a fixed array).
  std::size_t visit(const std::string& name, std::map<std::string, int>& state,
                    std::map<std::string, std::size_t>& unrolled) const {
    int& s = state[name];
    if (s == 2) return unrolled.at(name);
    if (s == 1) throw std::invalid_argument("message definition of " + main_ + ": type " + name + " contains itself");
    s = 1;
    constexpr std::size_t kOver = kMaxUnrolledFields + 1;
    std::size_t total = 0;
    for (const FieldDefinition& f : types_.at(name).fields) {
      std::size_t each = 1;
      if (!f.primitive) {
        if (types_.count(f.type_name) == 0) {
          throw std::invalid_argument("message definition of " + main_ + ": type " + f.type_name + " (field " + name +
                                      "." + f.name + ") is used but not defined");
        }
        each = 1 + visit(f.type_name, state, unrolled);
      }
      const std::size_t n = f.array == FieldDefinition::Array::fixed && !f.primitive ? f.fixed_length : 1;
      total = n > (kOver - std::min(total, kOver)) / each ? kOver : total + n * each;
    }
    if (total > kMaxUnrolledFields) {
      throw std::invalid_argument("message definition of " + main_ + ": type " + name + " has more than " +
                                  std::to_string(kMaxUnrolledFields) +
                                  " fields with its fixed arrays of messages unrolled");
    }
    state[name] = 2;
    unrolled[name] = total;
    return total;
  }

  std::string main_;
  std::map<std::string, TypeDefinition> types_;
};

}  // namespace streamclust::io::ros
