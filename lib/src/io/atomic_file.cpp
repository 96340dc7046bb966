// Every output file is written to a temporary name in its own directory and renamed, so a
// crash or kill -9 at any moment leaves either the old complete file or the new one.
#include "io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/output.hpp"

namespace stagger {
namespace io_detail {

namespace fs = std::filesystem;

namespace {
fs::path directory_of(const fs::path& path) {
  const fs::path parent = path.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}
}  // namespace

fs::path temporary_path(const fs::path& path) {
  // Built by appending: GCC 12 at -O3 warns falsely (-Wrestrict) on "." + std::string.
  std::string name(1, '.');
  name.append(path.filename().string()).append(".tmp.").append(std::to_string(::getpid()));
  return directory_of(path) / name;
}

void require_directory_of(const fs::path& path) {
  const fs::path directory = directory_of(path);
  std::error_code ec;
  const auto status = fs::status(directory, ec);
  if (!fs::exists(status)) {
    throw Error("cannot write '" + path.string() + "': directory '" + directory.string() +
                "' does not exist; create it or choose another output directory");
  }
  if (!fs::is_directory(status)) {
    throw Error("cannot write '" + path.string() + "': '" + directory.string() +
                "' is not a directory; choose another output directory");
  }
}

void replace_file(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(from, ignored);
    throw Error("cannot write '" + to.string() + "': renaming the temporary file failed (" + ec.message() +
                "); check the output directory's permissions");
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error("cannot read '" + path + "': " + std::strerror(errno) + "; check the path");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw Error("cannot read '" + path + "': read error");
  return buffer.str();
}

}  // namespace io_detail

void write_file_atomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  io_detail::require_directory_of(target);
  const fs::path temporary = io_detail::temporary_path(target);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw Error("cannot write '" + path + "': " + std::strerror(errno) +
                  "; check that the output directory is writable");
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw Error("cannot write '" + path + "': write failed (disk full?)");
    }
  }
  io_detail::replace_file(temporary, target);
}

}  // namespace stagger
