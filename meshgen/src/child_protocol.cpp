/// @file child_protocol.cpp
/// The bytes the gmsh child sends its parent (child_protocol.hpp): values in the machine's
/// own layout (parent and child are the same program), vectors and strings after their
/// 64-bit length.
#include "child_protocol.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

class Packer {
 public:
  template <class T>
  void value(const T& v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    value<std::uint64_t>(s.size());
    out_ += s;
  }
  void strings(const std::vector<std::string>& v) {
    value<std::uint64_t>(v.size());
    for (const auto& s : v) string(s);
  }
  const std::string& bytes() const { return out_; }

 private:
  std::string out_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& in) : in_(in) {}
  template <class T>
  T value() {
    T v{};
    take(&v, sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> vector() {
    const auto n = value<std::uint64_t>();
    if (n > (in_.size() - pos_) / sizeof(T)) throw std::runtime_error("truncated");
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto n = value<std::uint64_t>();
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::string s = in_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<std::string> strings() {
    const auto n = value<std::uint64_t>();
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::vector<std::string> v;
    for (std::uint64_t i = 0; i < n; ++i) v.push_back(string());
    return v;
  }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  void take(void* to, std::size_t n) {
    if (n > in_.size() - pos_) throw std::runtime_error("truncated");
    std::memcpy(to, in_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& in_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string pack(const PolygonSoup& soup) {
  Packer p;
  p.value<std::uint8_t>(0);
  p.vector(soup.x);
  p.vector(soup.y);
  p.vector(soup.polygon_begin);
  p.vector(soup.polygon_points);
  p.vector(soup.polygon_region);
  p.strings(soup.region_names);
  p.value<std::uint64_t>(soup.tagged_edges.size());
  for (const auto& e : soup.tagged_edges) {
    p.value(e.a);
    p.value(e.b);
    p.value(e.tag);
  }
  p.strings(soup.tag_names);
  p.string(soup.source);
  p.value(soup.unassigned_elements);
  p.strings(soup.notes);
  return p.bytes();
}

PolygonSoup unpack(const std::string& bytes) {
  Unpacker u(bytes);
  if (u.value<std::uint8_t>() != 0) throw Error(u.string());
  PolygonSoup soup;
  soup.x = u.vector<double>();
  soup.y = u.vector<double>();
  soup.polygon_begin = u.vector<std::int64_t>();
  soup.polygon_points = u.vector<std::int64_t>();
  soup.polygon_region = u.vector<int>();
  soup.region_names = u.strings();
  const auto nedges = u.value<std::uint64_t>();
  if (nedges > bytes.size()) throw std::runtime_error("truncated");
  for (std::uint64_t e = 0; e < nedges; ++e) {
    TaggedEdge edge;
    edge.a = u.value<std::int64_t>();
    edge.b = u.value<std::int64_t>();
    edge.tag = u.value<int>();
    soup.tagged_edges.push_back(edge);
  }
  soup.tag_names = u.strings();
  soup.source = u.string();
  soup.unassigned_elements = u.value<std::int64_t>();
  soup.notes = u.strings();
  if (!u.at_end()) throw std::runtime_error("trailing data");
  return soup;
}

std::string pack_failure(const std::string& message) {
  Packer p;
  p.value<std::uint8_t>(1);
  p.string(message);
  return p.bytes();
}

}  // namespace stagger::meshgen
