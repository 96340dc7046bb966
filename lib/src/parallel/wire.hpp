#pragma once
// A part's configuration on the wire (rank 0 to its rank, docs/parallel.md): plain bytes,
// sizes before arrays. A counting pass first (`counting`) sizes the buffer, so that packing
// never doubles it.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "stagger/error.hpp"

namespace stagger::parallel {

struct Packer {
  std::string data;
  bool counting = false;
  std::size_t size = 0;
  void append(const char* bytes, std::size_t n) {
    size += n;
    if (!counting) data.append(bytes, n);
  }
  template <class T>
  void value(const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    append(reinterpret_cast<const char*>(&x), sizeof x);
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(static_cast<std::uint64_t>(v.size()));
    append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& text) {
    value(static_cast<std::uint64_t>(text.size()));
    append(text.data(), text.size());
  }
};

struct Unpacker {
  explicit Unpacker(const std::string& d) : data(d) {}
  const std::string& data;
  std::size_t at = 0;
  void need(std::size_t n) const {
    if (n > data.size() - at) throw Error("internal: a part received from rank 0 is truncated");
  }
  template <class T>
  void value(T& x) {
    need(sizeof x);
    std::memcpy(&x, data.data() + at, sizeof x);
    at += sizeof x;
  }
  std::uint64_t count(std::size_t element) {
    std::uint64_t n = 0;
    value(n);
    if (n > (data.size() - at) / element) throw Error("internal: a part received from rank 0 is truncated");
    return n;
  }
  template <class T>
  void get(std::vector<T>& v) {
    v.resize(count(sizeof(T)));
    if (!v.empty()) std::memcpy(v.data(), data.data() + at, v.size() * sizeof(T));
    at += v.size() * sizeof(T);
  }
  void get(std::string& text) {
    text.assign(data.data() + at, count(1));
    at += text.size();
  }
  void expect_end() const {
    if (at != data.size()) throw Error("internal: a part received from rank 0 has trailing bytes");
  }
};

}  // namespace stagger::parallel
