/// @file geo_parameters.cpp
/// The parameter wrapper of a .geo (geo_parameters.hpp).
#include "geo_parameters.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

#include "fd_write.hpp"
#include "number_text.hpp"
#include "stagger/error.hpp"

namespace stagger::meshgen {
namespace {

/// Whether `word` occurs in `text` as a whole identifier.
bool contains_word(const std::string& text, const std::string& word) {
  const auto is_id = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; };
  for (auto pos = text.find(word); pos != std::string::npos; pos = text.find(word, pos + 1)) {
    const bool left = pos == 0 || !is_id(text[pos - 1]);
    const bool right = pos + word.size() == text.size() || !is_id(text[pos + word.size()]);
    if (left && right) return true;
  }
  return false;
}

}  // namespace

ParameterWrapper::ParameterWrapper(const std::string& path,
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
        std::all_of(name.begin(), name.end(), [](unsigned char ch) { return std::isalnum(ch) || ch == '_'; });
    if (!identifier) throw Error(path + ": parameter name '" + name + "' is not a valid .geo identifier");
    if (!contains_word(text, name))
      throw Error(path + ": unknown parameter '" + name + "' (the file never mentions it; check the spelling)");
    wrapper << name << " = " << number_text(value) << ";\n";
  }
  const std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
  const bool control =
      std::any_of(absolute.begin(), absolute.end(), [](unsigned char ch) { return ch < 0x20 || ch == 0x7f; });
  const char quote = absolute.find('"') == std::string::npos ? '"' : '\'';
  if (control || absolute.find(quote) != std::string::npos || absolute.size() > 1000)
    throw Error(path + ": gmsh cannot include this path with parameters (it " +
                (control                  ? std::string("contains a control character such as a newline")
                 : absolute.size() > 1000 ? std::string("is longer than 1000 characters")
                                          : std::string("contains both \" and ' quotes")) +
                "); rename the file or its directories");
  wrapper << "Include " << quote << absolute << quote << ";\n";
  std::string directory = (std::filesystem::temp_directory_path() / "stagger-geo-XXXXXX").string();
  if (!::mkdtemp(directory.data()))
    throw Error(path +
                ": cannot create a private temporary directory for the parameter wrapper: " + std::strerror(errno));
  directory_ = directory;
  file_ = (directory_ / "parameters.geo").string();
  const int fd = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  const std::string bytes = wrapper.str();
  const bool written = fd >= 0 && write_all(fd, bytes);
  if (fd >= 0) ::close(fd);
  if (!written) throw Error(path + ": cannot write the parameter wrapper in " + directory_.string());
}

ParameterWrapper::~ParameterWrapper() {
  std::error_code ec;
  if (!directory_.empty()) std::filesystem::remove_all(directory_, ec);
}

}  // namespace stagger::meshgen
