// The binary format of checkpoints: little-endian, bounds-checked (byte_stream.hpp).
#include "io/byte_stream.hpp"

#include <bit>
#include <cstring>

#include "stagger/error.hpp"

namespace stagger::io_detail {

namespace {
constexpr bool kLittleEndianHost = std::endian::native == std::endian::little;
constexpr std::uint64_t kFnv1aPrime = 1099511628211ull;
}  // namespace

std::uint64_t fnv1a64(std::string_view data, std::uint64_t hash) {
  for (const char c : data) hash = (hash ^ static_cast<unsigned char>(c)) * kFnv1aPrime;
  return hash;
}

std::uint64_t fnv1a64(std::uint64_t value, std::uint64_t hash) {
  for (int k = 0; k < 8; ++k) hash = (hash ^ ((value >> (8 * k)) & 0xffu)) * kFnv1aPrime;
  return hash;
}

std::uint64_t fnv1a64(std::span<const double> values, std::uint64_t hash) {
  for (const double v : values) hash = fnv1a64(std::bit_cast<std::uint64_t>(v), hash);
  return hash;
}

void ByteWriter::u64(std::uint64_t value) {
  char bytes[8];
  for (int k = 0; k < 8; ++k) bytes[k] = static_cast<char>((value >> (8 * k)) & 0xffu);
  append(bytes, 8);
}

void ByteWriter::f64(double value) {
  u64(std::bit_cast<std::uint64_t>(value));
}

void ByteWriter::bytes(std::string_view text) {
  u64(text.size());
  append(text.data(), text.size());
}

void ByteWriter::doubles(std::span<const double> values) {
  u64(values.size());
  if constexpr (kLittleEndianHost) {
    append(reinterpret_cast<const char*>(values.data()), values.size_bytes());
  } else {
    for (const double v : values) f64(v);
  }
}

void ByteReader::fail(const std::string& message) const {
  throw Error(source_ + ": " + message);
}

void ByteReader::need(std::uint64_t size) const {
  if (size > data_.size() - position_) {
    fail("truncated or corrupt (needs " + std::to_string(size) + " more bytes at offset " + std::to_string(position_) +
         ", has " + std::to_string(data_.size() - position_) + ")");
  }
}

void ByteReader::copy_out(void* to, std::size_t n) {
  if (n > 0) std::memcpy(to, data_.data() + position_, n);  // empty: no pointer
  position_ += n;
}

std::uint8_t ByteReader::u8() {
  need(1);
  return static_cast<std::uint8_t>(data_[position_++]);
}

std::uint64_t ByteReader::u64() {
  need(8);
  std::uint64_t value = 0;
  for (int k = 0; k < 8; ++k)
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[position_ + k])) << (8 * k);
  position_ += 8;
  return value;
}

double ByteReader::f64() {
  return std::bit_cast<double>(u64());
}

std::string_view ByteReader::bytes_view() {
  const std::uint64_t size = u64();
  need(size);
  const std::string_view text = data_.substr(position_, size);
  position_ += size;
  return text;
}

bool ByteReader::raw_equals(std::string_view text) {
  need(text.size());
  const bool equal = data_.substr(position_, text.size()) == text;
  position_ += text.size();
  return equal;
}

void ByteReader::doubles(std::span<double> out, std::string_view what) {
  const std::uint64_t count = u64();
  if (count != out.size()) {
    fail("field '" + std::string(what) + "' has " + std::to_string(count) + " values, expected " +
         std::to_string(out.size()));
  }
  need(count * 8);  // count == out.size(): no overflow
  if constexpr (kLittleEndianHost) {
    if (count > 0) std::memcpy(out.data(), data_.data() + position_, count * 8);  // empty: no pointer
    position_ += count * 8;
  } else {
    for (double& v : out) v = f64();
  }
}

std::uint64_t ByteReader::count(std::size_t min_item_size, std::string_view what) {
  const std::uint64_t n = u64();
  if (n > remaining() / min_item_size) {
    fail("is corrupt: " + std::to_string(n) + " " + std::string(what) + " cannot fit in the " +
         std::to_string(remaining()) + " bytes left");
  }
  return n;
}

std::uint64_t ByteReader::skip_doubles() {
  const std::uint64_t count = u64();
  if (count > (data_.size() - position_) / 8) need(data_.size() - position_ + 1);  // reports the truncation
  position_ += count * 8;
  return count;
}

void ByteReader::expect_end() const {
  if (!at_end()) {
    fail("has " + std::to_string(data_.size() - position_) + " bytes of trailing data at offset " +
         std::to_string(position_) + "; it is corrupt");
  }
}

}  // namespace stagger::io_detail
