#pragma once
/// @file output_directory.hpp
/// A run's output directory (internal to lib/src/driver): created and probed, locked for one
/// run, cleared of the files this program made and no other, and refused when it holds another
/// scene's results (docs/output.md, "One run per directory" and after).
#include <filesystem>
#include <string>
#include <vector>

namespace stagger::driver_detail {

/// True if `file` (a bare file name) is one of the outputs a run named `name` writes: its
/// `.pvd`, its numbered dumps (`name_NNNNNN.vtu`, `.pvtu`, `name_NNNNNN_rRRRR.vtu`), its
/// checkpoint and a distributed checkpoint's pieces (`name.checkpoint.P.rRRRR`).
bool is_output_of(const std::string& name, const std::string& file);

class OutputDirectory {
 public:
  explicit OutputDirectory(std::filesystem::path directory);
  ~OutputDirectory();  ///< unlocks, removing the lock file
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::filesystem::path& path() const { return directory_; }

  /// Creates the directory if needed, proves it writable (a private directory made and
  /// removed), and removes what dead writers of this program left (their private
  /// directories, `.stagger-tmp.<pid>.XXXXXX`, never a file of another name).
  void prepare() const;
  /// One run per directory: an exclusive flock on `.stagger.lock` (opened without following
  /// a link; a lock file replaced while waiting is locked again). Throws naming the owner's pid.
  void lock();
  /// Refuses a directory holding the results of another run than `name` (a .pvd or checkpoint
  /// of another name, or a summary.json naming another scene than `scene`), unless `replace`:
  /// then those results (and the shared history.csv, summary.json, ranks.csv) are removed.
  /// Throws naming the other scene.
  void claim(const std::string& name, const std::string& scene, bool replace) const;
  /// A fresh run: removes this name's previous outputs (its .pvd, dumps and checkpoints), so no
  /// stale dump or checkpoint lies beside the new run's.
  void remove_outputs_of(const std::string& name) const;
  /// True if `file` (relative to the directory) is a regular file there.
  bool holds(const std::string& file) const;

 private:
  void remove_stale_private_directories() const;
  std::vector<std::filesystem::path> files_of(const std::string& name) const;

  std::filesystem::path directory_;
  int lock_fd_ = -1;
};

}  // namespace stagger::driver_detail
