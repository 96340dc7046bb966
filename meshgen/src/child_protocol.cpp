/// @file child_protocol.cpp
/// The bytes the gmsh child sends its parent (child_protocol.hpp), in the library's one byte
/// stream (lib/src/io/byte_stream.hpp): arrays in the machine's own layout (parent and child
/// are the same program), strings after their 64-bit length.
#include "child_protocol.hpp"

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "io/byte_stream.hpp"
#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

using io_detail::ByteReader;
using io_detail::ByteWriter;

void put_strings(ByteWriter& out, const std::vector<std::string>& strings) {
  out.u64(strings.size());
  for (const std::string& s : strings) out.bytes(s);
}

std::vector<std::string> get_strings(ByteReader& in) {
  std::vector<std::string> strings(in.count(8, "strings"));
  for (std::string& s : strings) s = in.bytes();
  return strings;
}

}  // namespace

std::string pack(const PolygonSoup& soup) {
  ByteWriter out;
  out.u8(0);
  out.native_array(soup.x);
  out.native_array(soup.y);
  out.native_array(soup.polygon_begin);
  out.native_array(soup.polygon_points);
  out.native_array(soup.polygon_region);
  put_strings(out, soup.region_names);
  out.native_array(soup.tagged_edges);
  put_strings(out, soup.tag_names);
  out.bytes(soup.source);
  out.native(soup.unassigned_elements);
  put_strings(out, soup.notes);
  return out.take();
}

PolygonSoup unpack(const std::string& bytes) {
  ByteReader in(bytes, "the gmsh child's answer");
  std::uint8_t kind = 1;
  PolygonSoup soup;
  try {
    kind = in.u8();
    if (kind == 0) {
      in.native_array(soup.x, "x");
      in.native_array(soup.y, "y");
      in.native_array(soup.polygon_begin, "polygon offsets");
      in.native_array(soup.polygon_points, "polygon points");
      in.native_array(soup.polygon_region, "polygon regions");
      soup.region_names = get_strings(in);
      in.native_array(soup.tagged_edges, "tagged edges");
      soup.tag_names = get_strings(in);
      soup.source = in.bytes();
      in.native(soup.unassigned_elements);
      soup.notes = get_strings(in);
      in.expect_end();
      return soup;
    }
  } catch (const Error& e) {
    throw std::runtime_error(e.what());  // a cut answer: the child ended before it finished
  }
  std::string message;
  try {
    message = in.bytes();
  } catch (const Error& e) {
    throw std::runtime_error(e.what());
  }
  throw Error(message);
}

std::string pack_failure(const std::string& message) {
  ByteWriter out;
  out.u8(1);
  out.bytes(message);
  return out.take();
}

}  // namespace stagger::meshgen
