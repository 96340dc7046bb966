/// @file gmsh_io.cpp
/// .geo and .msh files through the gmsh 4.8 C++ API, and MSH 4.1 output. gmsh is a global
/// singleton that is not thread-safe: every use holds one mutex and one RAII session
/// (initialize ... finalize), so no gmsh state leaks from one call to the next.
#include <gmsh.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include <sys/wait.h>
#include <unistd.h>

#include "stagger/error.hpp"
#include "stagger/meshgen.hpp"

namespace stagger::meshgen {
namespace {

// MSH element types (gmsh reference manual, "MSH file format").
constexpr int kLine2 = 1, kTriangle3 = 2, kQuad4 = 3;

std::mutex& gmsh_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::string number_text(double value) {
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

/// One gmsh session: initialize, quiet terminal, logger on; finalize on destruction.
class GmshSession {
public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    // STAGGER_GMSH_VERBOSE=1 shows gmsh's own messages (debugging a .geo).
    const char* verbose = std::getenv("STAGGER_GMSH_VERBOSE");
    gmsh::option::setNumber("General.Terminal", verbose && *verbose && *verbose != '0' ? 1 : 0);
    // Errors are read from the logger after each step: with the default (2) gmsh throws
    // from inside its mesher, where an exception can end in std::terminate.
    gmsh::option::setNumber("General.AbortOnError", 0);
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {  // a destructor must not throw; gmsh throws std::string
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The first and last errors gmsh logged since the session started, or "".
  static std::string errors() {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string first;
    for (const auto& line : log)
      if (line.rfind("Error", 0) == 0) {
        first = line;
        break;
      }
    std::string last;
    gmsh::logger::getLastError(last);
    for (std::string* text : {&first, &last}) {
      for (const char* prefix : {"Error   : ", "Error : ", "Error: "})
        if (text->rfind(prefix, 0) == 0) text->erase(0, std::string(prefix).size());
    }
    if (first.empty()) return last;
    if (last.empty() || first.find(last) != std::string::npos) return first;
    return first + " ... " + last;
  }
};

/// Runs `body` in a gmsh session, turning gmsh's std::string exceptions and logged errors
/// into stagger::Error naming the file.
template <class Body>
auto in_gmsh_session(const std::string& path, Body body) {
  GmshSession session;
  try {
    return body();
  } catch (const std::string& message) {
    const std::string logged = GmshSession::errors();
    throw Error("gmsh failed on " + path + ": " + (logged.empty() ? message : logged));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& failure) {
    // gmsh's readers trust the file: a corrupt count or element type ends in e.g.
    // std::bad_array_new_length or std::bad_alloc (found by fuzzing read_msh).
    const std::string logged = GmshSession::errors();
    throw Error("gmsh failed on " + path + ": " + (logged.empty() ? std::string(failure.what()) : logged) +
                "; the file is corrupt or not a valid MSH/.geo file");
  }
}

template <class Body>
auto with_gmsh(const std::string& path, Body body) {
  std::lock_guard lock(gmsh_mutex());
  return in_gmsh_session(path, body);
}

// --- Reading a .msh in a child process -------------------------------------------------
// gmsh 4.8's MSH reader trusts the file: an element that names a missing node, or a
// corrupt section, can crash it (segfault, double free) instead of reporting an error
// (found by fuzzing read_msh, docs/robustness.md). The reader therefore runs in a forked
// child that sends the soup (or the error) back through a pipe; a crash becomes a
// stagger::Error naming the file. STAGGER_GMSH_IN_PROCESS=1 reads in-process (debugging).

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
  if (!u.at_end()) throw std::runtime_error("trailing data");
  return soup;
}

bool write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

/// Runs `read` (which returns a soup) in a gmsh session in a child process.
template <class Read>
PolygonSoup read_isolated(const std::string& path, Read read) {
  const char* in_process = std::getenv("STAGGER_GMSH_IN_PROCESS");
  if (in_process && *in_process && *in_process != '0') return with_gmsh(path, read);
  // Hold the gmsh lock across the fork: no other thread is inside gmsh, and the child
  // (whose only thread is this one) must not lock it again.
  std::lock_guard lock(gmsh_mutex());
  int fds[2];
  if (::pipe(fds) != 0) throw Error("cannot read " + path + ": pipe() failed");
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error("cannot read " + path + ": fork() failed");
  }
  if (child == 0) {
    ::close(fds[0]);
    std::string message;
    try {
      message = pack(in_gmsh_session(path, read));
    } catch (const Error& failure) {
      Packer p;
      p.value<std::uint8_t>(1);
      p.string(failure.what());
      message = p.bytes();
    } catch (...) {
      Packer p;
      p.value<std::uint8_t>(1);
      p.string("gmsh failed on " + path + ": unexpected exception");
      message = p.bytes();
    }
    ::_exit(write_all(fds[1], message) ? 0 : 3);  // no atexit handlers, no stdio flush
  }
  ::close(fds[1]);
  std::string bytes;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw Error("gmsh crashed (signal " + std::to_string(WTERMSIG(status)) + ", " + strsignal(WTERMSIG(status)) +
                ") reading " + path +
                ": the file is corrupt (e.g. an element refers to a node that $Nodes does not define); "
                "check it with 'gmsh " + path + " -0' or re-export it");
  try {
    return unpack(bytes);
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    throw Error("gmsh failed reading " + path + ": the reader process ended early (exit status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
}

void throw_if_gmsh_error(const std::string& path, const std::string& doing) {
  const std::string logged = GmshSession::errors();
  if (!logged.empty())
    throw Error("gmsh failed " + doing + " " + path + ": " + logged +
                (doing == "reading" ? "; fix the file (STAGGER_GMSH_VERBOSE=1 shows gmsh's messages)" : ""));
}

void require_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(what + " '" + path + "' not found (or not a regular file); check the path");
}

std::string physical_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  if (!name.empty()) return name;
  return (dim == 2 ? "surface_" : "curve_") + std::to_string(tag);
}

std::string element_name(int type) {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary = 0;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
  return name;
}

/// The current gmsh model's physical surfaces and curves as a polygon soup.
PolygonSoup extract_soup(const std::string& path) {
  PolygonSoup soup;
  soup.source = path;
  std::vector<std::size_t> poly_nodes;  // gmsh node tags, translated at the end
  std::vector<std::size_t> edge_nodes;
  std::vector<int> edge_tag;

  // Regions: physical surfaces by name; without any, every surface entity is a region.
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  std::vector<std::pair<std::string, std::vector<int>>> regions;
  if (groups.empty()) {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, 2);
    for (const auto& [dim, tag] : entities)
      regions.push_back({"surface_" + std::to_string(tag), {tag}});
  } else {
    for (const auto& [dim, tag] : groups) {
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
      regions.push_back({physical_name(dim, tag), entities});
    }
  }
  std::map<int, std::string> entity_region;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    soup.region_names.push_back(regions[r].first);
    for (int entity : regions[r].second) {
      const auto [it, fresh] = entity_region.emplace(entity, regions[r].first);
      if (!fresh)
        throw Error(path + ": surface " + std::to_string(entity) + " is in two physical "
                    "surfaces, '" + it->second + "' and '" + regions[r].first +
                    "'; a zone can belong to one region only");
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        const std::size_t n = types[k] == kTriangle3 ? 3 : types[k] == kQuad4 ? 4 : 0;
        if (n == 0)
          throw Error(path + ": surface " + std::to_string(entity) + " has elements of type '" +
                      element_name(types[k]) +
                      "'; only first-order triangles and quadrangles are supported "
                      "(set Mesh.ElementOrder = 1)");
        const auto& nodes = node_tags[k];
        for (std::size_t e = 0; e + n <= nodes.size(); e += n) {
          soup.polygon_begin.push_back(soup.polygon_begin.back() + static_cast<std::int64_t>(n));
          soup.polygon_region.push_back(static_cast<int>(r));
          poly_nodes.insert(poly_nodes.end(), nodes.begin() + static_cast<std::ptrdiff_t>(e),
                            nodes.begin() + static_cast<std::ptrdiff_t>(e + n));
        }
      }
    }
  }
  if (poly_nodes.empty())
    throw Error("empty mesh: " + path + " gave no 2D elements" +
                (groups.empty() ? std::string(" (and it defines no physical surface)")
                                : std::string(" in its physical surfaces")) +
                "; check the geometry and its Physical Surface definitions");

  // Tags: physical curves, their 2-node line elements.
  gmsh::vectorpair curves;
  gmsh::model::getPhysicalGroups(curves, 1);
  for (const auto& [dim, tag] : curves) {
    const int t = static_cast<int>(soup.tag_names.size());
    soup.tag_names.push_back(physical_name(dim, tag));
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    for (int entity : entities) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> element_tags, node_tags;
      gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, entity);
      for (std::size_t k = 0; k < types.size(); ++k) {
        if (types[k] != kLine2)
          throw Error(path + ": curve " + std::to_string(entity) + " of physical curve '" +
                      soup.tag_names.back() + "' has elements of type '" +
                      element_name(types[k]) + "'; only 2-node lines are supported");
        for (std::size_t e = 0; e + 2 <= node_tags[k].size(); e += 2) {
          edge_nodes.push_back(node_tags[k][e]);
          edge_nodes.push_back(node_tags[k][e + 1]);
          edge_tag.push_back(t);
        }
      }
    }
  }

  // Points: only the nodes that zones use (gmsh also returns orphans such as circle
  // centres), numbered in increasing gmsh tag order (tags need not be contiguous).
  std::vector<std::size_t> used = poly_nodes;
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, std::int64_t> index;
  index.reserve(used.size());
  for (std::size_t i = 0; i < used.size(); ++i) index.emplace(used[i], static_cast<std::int64_t>(i));
  std::vector<std::size_t> node_tags;
  std::vector<double> coord, parametric;
  gmsh::model::mesh::getNodes(node_tags, coord, parametric, -1, -1, false, false);
  soup.x.assign(used.size(), 0.0);
  soup.y.assign(used.size(), 0.0);
  std::vector<char> found(used.size(), 0);
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    const auto it = index.find(node_tags[k]);
    if (it == index.end()) continue;
    const auto i = static_cast<std::size_t>(it->second);
    soup.x[i] = coord[3 * k];
    soup.y[i] = coord[3 * k + 1];
    found[i] = 1;
  }
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!found[i])
      throw Error(path + ": element node " + std::to_string(used[i]) + " has no coordinates");
  soup.polygon_points.reserve(poly_nodes.size());
  for (std::size_t node : poly_nodes) soup.polygon_points.push_back(index.at(node));
  for (std::size_t e = 0; e < edge_tag.size(); ++e) {
    const auto a = index.find(edge_nodes[2 * e]), b = index.find(edge_nodes[2 * e + 1]);
    if (a == index.end() || b == index.end())
      throw Error(path + ": physical curve '" + soup.tag_names[static_cast<std::size_t>(edge_tag[e])] +
                  "' has an edge (nodes " + std::to_string(edge_nodes[2 * e]) + ", " +
                  std::to_string(edge_nodes[2 * e + 1]) +
                  ") that bounds no zone of a physical surface; tag only curves of the meshed domain");
    soup.tagged_edges.push_back({a->second, b->second, edge_tag[e]});
  }
  return soup;
}

std::size_t count_triangles(const PolygonSoup& soup) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < soup.num_polygons(); ++f)
    n += soup.polygon_begin[f + 1] - soup.polygon_begin[f] == 3 ? 1 : 0;
  return n;
}

/// Counts triangles in the current gmsh mesh of dimension 2.
std::size_t gmsh_triangles() {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
  std::size_t n = 0;
  for (std::size_t k = 0; k < types.size(); ++k)
    if (types[k] == kTriangle3) n += element_tags[k].size();
  return n;
}

/// Subdivide policy after meshing: if triangles are left, split every element into quads
/// (gmsh's all-quad subdivision: each quad into 4, each triangle into 3, so the element
/// size halves).
void subdivide_if_triangles() {
  if (gmsh_triangles() == 0) return;
  gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 1);
  gmsh::model::mesh::refine();
}

void apply_policy(const PolygonSoup& soup, TrianglePolicy policy) {
  if (policy != TrianglePolicy::reject) return;
  const std::size_t n = count_triangles(soup);
  if (n > 0)
    throw Error(soup.source + ": " + std::to_string(n) + " of " +
                std::to_string(soup.num_polygons()) +
                " zones are triangles and the triangle policy is 'reject'; use 'accept' "
                "(mixed zones) or 'subdivide' (all quads), or make the surface transfinite");
}

/// Parameters of a .geo, like `gmsh -setnumber NAME VALUE`. gmsh 4.8 keeps -setnumber values
/// passed to gmsh::initialize in a static table that finalize() does not clear, so they
/// would leak into every later file of the process. Instead, a small wrapper file defines
/// the parameters and includes the .geo: DefineConstant keeps a value that is already
/// defined, exactly as with -setnumber, and open() clears the parser variables each time.
class ParameterWrapper {
public:
  ParameterWrapper(const std::string& path,
                   const std::vector<std::pair<std::string, double>>& parameters) {
    if (parameters.empty()) {
      file_ = path;
      return;
    }
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ostringstream wrapper;
    for (const auto& [name, value] : parameters) {
      const bool identifier =
          !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
          std::all_of(name.begin(), name.end(), [](unsigned char ch) {
            return std::isalnum(ch) || ch == '_';
          });
      if (!identifier)
        throw Error(path + ": parameter name '" + name + "' is not a valid .geo identifier");
      if (!contains_word(text, name))
        throw Error(path + ": unknown parameter '" + name +
                    "' (the file never mentions it; check the spelling)");
      wrapper << name << " = " << number_text(value) << ";\n";
    }
    wrapper << "Include \"" << std::filesystem::absolute(path).string() << "\";\n";
    static unsigned counter = 0;  // under gmsh_mutex()
    temp_ = std::filesystem::temp_directory_path() /
            ("stagger_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".geo");
    std::ofstream(temp_) << wrapper.str();
    file_ = temp_.string();
  }
  ~ParameterWrapper() {
    std::error_code ec;
    if (!temp_.empty()) std::filesystem::remove(temp_, ec);
  }
  ParameterWrapper(const ParameterWrapper&) = delete;
  ParameterWrapper& operator=(const ParameterWrapper&) = delete;
  const std::string& file() const { return file_; }

private:
  static bool contains_word(const std::string& text, const std::string& word) {
    const auto is_id = [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
    };
    for (auto pos = text.find(word); pos != std::string::npos; pos = text.find(word, pos + 1)) {
      const bool left = pos == 0 || !is_id(text[pos - 1]);
      const bool right = pos + word.size() == text.size() || !is_id(text[pos + word.size()]);
      if (left && right) return true;
    }
    return false;
  }
  std::string file_;
  std::filesystem::path temp_;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return ext;
}

}  // namespace

PolygonSoup read_geo(const std::string& path, const GeoOptions& options) {
  require_file(path, "geometry file");
  PolygonSoup soup = with_gmsh(path, [&] {
    const ParameterWrapper wrapper(path, options.parameters);
    gmsh::open(wrapper.file());
    throw_if_gmsh_error(path, "reading");
    // Options after open(): the file may set its own. Algorithm 8 segfaults in Debian's
    // gmsh 4.8, so fall back to 6 (Frontal-Delaunay) and recombine.
    double algorithm = 0;
    gmsh::option::getNumber("Mesh.Algorithm", algorithm);
    if (algorithm == 8) gmsh::option::setNumber("Mesh.Algorithm", 6);
    if (options.recombine) {
      gmsh::option::setNumber("Mesh.RecombineAll", 1);
      // 1: blossom. The full-quad variants (2, 3) fail ("1D mesh cannot be divided by 2")
      // on transfinite curves with an odd number of segments, so the subdivide policy
      // recombines with blossom too and then subdivides if triangles are left.
      gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
    }
    gmsh::model::mesh::generate(2);
    throw_if_gmsh_error(path, "meshing");
    if (options.triangles == TrianglePolicy::subdivide) {
      subdivide_if_triangles();
      throw_if_gmsh_error(path, "subdividing");
    }
    return extract_soup(path);
  });
  apply_policy(soup, options.triangles);
  return soup;
}

PolygonSoup read_msh(const std::string& path, TrianglePolicy triangles) {
  require_file(path, "mesh file");
  PolygonSoup soup = read_isolated(path, [&] {
    gmsh::open(path);
    throw_if_gmsh_error(path, "reading");
    if (triangles == TrianglePolicy::subdivide) {
      subdivide_if_triangles();
      throw_if_gmsh_error(path, "subdividing");
    }
    return extract_soup(path);
  });
  apply_policy(soup, triangles);
  return soup;
}

PolygonSoup read_mesh_file(const std::string& path, const GeoOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".geo") return read_geo(path, options);
  if (ext == ".msh") {
    if (!options.parameters.empty())
      throw Error(path + ": parameters (" + options.parameters.front().first +
                  " ...) only apply to .geo files, not to a .msh mesh");
    return read_msh(path, options.triangles);
  }
  throw Error("'" + path + "': unknown mesh file extension '" + ext + "'; use .geo or .msh");
}

void write_msh(const std::string& path, const Mesh& mesh) {
  if (mesh.num_zones() == 0) throw Error("write_msh: the mesh has no zones (" + path + ")");
  for (Index z = 0; z < mesh.num_zones(); ++z) {
    const Index n = mesh.zone_corner_begin[z + 1] - mesh.zone_corner_begin[z];
    if (n != 3 && n != 4)
      throw Error("write_msh " + path + ": zone " + std::to_string(z) + " has " +
                  std::to_string(n) + " corners; MSH stores only triangles and quadrangles");
  }
  with_gmsh(path, [&] {
    gmsh::model::add("stagger");
    // One discrete surface per region (tag r+1), one discrete curve per boundary tag.
    // All nodes live on the first region's surface; elements may use any node.
    const Index nregions = mesh.num_regions();
    for (Index r = 0; r < nregions; ++r) gmsh::model::addDiscreteEntity(2, r + 1);
    const int node_entity = mesh.zone_region[0] + 1;
    std::vector<std::size_t> node_tags(static_cast<std::size_t>(mesh.num_points()));
    std::vector<double> coord(3 * node_tags.size(), 0.0);
    for (std::size_t p = 0; p < node_tags.size(); ++p) {
      node_tags[p] = p + 1;
      coord[3 * p] = mesh.x[p];
      coord[3 * p + 1] = mesh.y[p];
    }
    gmsh::model::mesh::addNodes(2, node_entity, node_tags, coord);
    std::size_t element = 1;
    for (Index r = 0; r < nregions; ++r) {
      std::vector<std::size_t> tri_tags, tri_nodes, quad_tags, quad_nodes;
      for (Index z = mesh.region_zone_begin[r]; z < mesh.region_zone_begin[r + 1]; ++z) {
        const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
        auto& tags = e - b == 3 ? tri_tags : quad_tags;
        auto& nodes = e - b == 3 ? tri_nodes : quad_nodes;
        tags.push_back(element++);
        for (Index c = b; c < e; ++c) nodes.push_back(static_cast<std::size_t>(mesh.corner_point[c]) + 1);
      }
      if (!tri_tags.empty())
        gmsh::model::mesh::addElementsByType(r + 1, kTriangle3, tri_tags, tri_nodes);
      if (!quad_tags.empty())
        gmsh::model::mesh::addElementsByType(r + 1, kQuad4, quad_tags, quad_nodes);
      gmsh::model::addPhysicalGroup(2, {r + 1}, r + 1);
      gmsh::model::setPhysicalName(2, r + 1, mesh.region_names[static_cast<std::size_t>(r)]);
    }
    for (std::size_t t = 0; t < mesh.tags.size(); ++t) {
      const int entity = static_cast<int>(t) + 1;
      gmsh::model::addDiscreteEntity(1, entity);
      std::vector<std::size_t> line_tags, line_nodes;
      for (const auto& edge : mesh.tags[t].edges) {
        line_tags.push_back(element++);
        line_nodes.push_back(static_cast<std::size_t>(edge[0]) + 1);
        line_nodes.push_back(static_cast<std::size_t>(edge[1]) + 1);
      }
      if (!line_tags.empty())
        gmsh::model::mesh::addElementsByType(entity, kLine2, line_tags, line_nodes);
      gmsh::model::addPhysicalGroup(1, {entity}, entity);
      gmsh::model::setPhysicalName(1, entity, mesh.tags[t].name);
    }
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);  // exact doubles (ASCII MSH prints 16 digits)
    gmsh::write(path);
    throw_if_gmsh_error(path, "writing");
  });
}

}  // namespace stagger::meshgen
