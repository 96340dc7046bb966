#pragma once
/// @file byte_stream.hpp
/// The one binary format of the library's own files (checkpoints, docs/output.md): fixed-width
/// little-endian integers, IEEE-754 doubles as their bit patterns (a restart is bitwise),
/// length-prefixed byte strings and double arrays, and an FNV-1a 64 checksum. The byte order
/// is fixed, not the host's, so a file means the same on every machine; every read is
/// bounds-checked and its errors name the source (the file).
///
/// The same writer and reader carry the bytes that never leave the program (a part on the
/// MPI wire between ranks of one binary, the gmsh child's answer through its pipe): those may
/// add `native` values and arrays, trivially copyable types in the host's own layout (structs
/// included), which a file never holds. A counting writer sizes a buffer before the real pass,
/// so that packing a large message never doubles it.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace stagger::io_detail {

static_assert(std::numeric_limits<double>::is_iec559 && sizeof(double) == 8,
              "the binary format stores IEEE-754 binary64 doubles");

/// FNV-1a 64 (Fowler, Noll, Vo): h = (h xor byte) * 1099511628211 from 14695981039346656037.
/// Each byte step is a bijection of the state, so any change of one byte changes the hash.
inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;
std::uint64_t fnv1a64(std::string_view data, std::uint64_t hash = kFnv1aOffset);
/// The same over the 8 bytes of `value`, little-endian (as ByteWriter::u64 writes it).
std::uint64_t fnv1a64(std::uint64_t value, std::uint64_t hash);
/// The same over the bytes of the little-endian encoding of `values` (as ByteWriter writes them).
std::uint64_t fnv1a64(std::span<const double> values, std::uint64_t hash = kFnv1aOffset);

class ByteWriter {
 public:
  /// A writer that only counts the bytes it would write (`size()`), holding none.
  static ByteWriter counter() {
    ByteWriter w;
    w.counting_ = true;
    return w;
  }
  void reserve(std::size_t bytes) { out_.reserve(bytes); }
  /// The bytes written (or counted) so far.
  std::size_t size() const { return size_; }
  void u8(std::uint8_t value) {
    const char byte = static_cast<char>(value);
    append(&byte, 1);
  }
  void u64(std::uint64_t value);
  void i64(std::int64_t value) { u64(static_cast<std::uint64_t>(value)); }
  void f64(double value);
  /// Length (u64) then the bytes.
  void bytes(std::string_view text);
  /// Count (u64) then the values.
  void doubles(std::span<const double> values);
  /// The bytes as they are, no length (magic numbers, nested blocks of known length).
  void raw(std::string_view text) { append(text.data(), text.size()); }
  /// A value in the host's layout (same-program transport only, see above).
  template <class T>
  void native(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  /// Count (u64) then the values in the host's layout (same-program transport only).
  template <class T>
  void native_array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    u64(values.size());
    append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  const std::string& data() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  void append(const char* bytes, std::size_t n) {
    size_ += n;
    if (!counting_ && n > 0) out_.append(bytes, n);
  }
  std::string out_;
  std::size_t size_ = 0;
  bool counting_ = false;
};

class ByteReader {
 public:
  /// `source` names the data in errors, e.g. "checkpoint 'out/sod.checkpoint'".
  ByteReader(std::string_view data, std::string source) : data_(data), source_(std::move(source)) {}
  std::uint8_t u8();
  std::uint64_t u64();
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  double f64();
  std::string bytes() { return std::string(bytes_view()); }
  std::string_view bytes_view();
  /// Reads `text.size()` bytes and says whether they equal `text`.
  bool raw_equals(std::string_view text);
  /// Reads a double array of exactly `out.size()` values into `out`; a count that differs
  /// is an error naming `what`.
  void doubles(std::span<double> out, std::string_view what);
  /// A value in the host's layout, as ByteWriter::native wrote it.
  template <class T>
  void native(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof value);
    copy_out(&value, sizeof value);
  }
  /// An array as ByteWriter::native_array wrote it; its count is bounded by the bytes left.
  template <class T>
  void native_array(std::vector<T>& values, std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    values.resize(count(sizeof(T), what));
    copy_out(values.data(), values.size() * sizeof(T));
  }
  /// Skips a double array, returning its count.
  std::uint64_t skip_doubles();
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return data_.size() - position_; }
  /// Reads a count of items that take at least `min_item_size` bytes each; a count the
  /// remaining bytes cannot hold is an error naming `what` (no huge allocation from a bad file).
  std::uint64_t count(std::size_t min_item_size, std::string_view what);
  bool at_end() const { return position_ == data_.size(); }
  /// Throws unless every byte was read.
  void expect_end() const;
  /// Throws stagger::Error "<source>: <message>".
  [[noreturn]] void fail(const std::string& message) const;
  const std::string& source() const { return source_; }

 private:
  void need(std::uint64_t size) const;
  void copy_out(void* to, std::size_t n);  // n bytes already checked by need() or count()
  std::string_view data_;
  std::size_t position_ = 0;
  std::string source_;
};

}  // namespace stagger::io_detail
