// `stagger run` under mpirun (mpi_session.hpp, docs/parallel.md).
#include "mpi_session.hpp"

#include <sys/resource.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "stagger/output.hpp"

#ifdef STAGGER_WITH_MPI
#include "stagger/parallel.hpp"
#endif

namespace stagger::cli {

MpiState& mpi_state() {
  static MpiState state;
  return state;
}

void start_mpi_if_launched() {
#ifdef STAGGER_WITH_MPI
  // Open MPI's mpirun and the PMI/PMIx launchers set these in every process they start.
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
  MpiState& state = mpi_state();
  if (!launched || state.active) return;
  // gmsh meshes in a child process (fork): Open MPI's warning about it does not apply.
  ::setenv("OMPI_MCA_mpi_warn_on_fork", "0", 0);
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);  // OpenMP threads never call MPI
  state.active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &state.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &state.ranks);
#endif
}

void finish_mpi() {
#ifdef STAGGER_WITH_MPI
  MpiState& state = mpi_state();
  if (state.active) MPI_Finalize();
  state.active = false;
#endif
}

void abort_mpi() {
#ifdef STAGGER_WITH_MPI
  if (mpi_state().active) MPI_Abort(MPI_COMM_WORLD, 1);
#endif
  std::exit(1);
}

void on_every_rank(const std::function<void()>& work) {
#ifdef STAGGER_WITH_MPI
  if (mpi_state().active) {
    try {
      stagger::on_every_rank(MPI_COMM_WORLD, work);
    } catch (const CollectiveError&) {
      throw;
    } catch (const Error& error) {
      throw CollectiveError(error.what());
    }
    return;
  }
#endif
  work();
}

namespace {

// FNV-1a, 64 bits: a digest to compare, not a defence against a crafted collision.
std::uint64_t digest(const std::string& text, std::uint64_t hash = 0xcbf29ce484222325ULL) {
  for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return hash;
}

std::uint64_t digest(const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::uint64_t hash = digest(std::to_string(pairs.size()));
  for (const auto& [key, value] : pairs) hash = digest(value, digest(key + '\0' + std::to_string(value.size()), hash));
  return hash;
}

// The scene file's text, or a text that says why it cannot be read (so that a rank that
// cannot read it differs from one that can).
std::string scene_text(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::string("\x01not a regular file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return in ? text.str() : std::string("\x01unreadable");
}

}  // namespace

void compare_start_on_every_rank([[maybe_unused]] const std::string& scene_path,
                                 [[maybe_unused]] const std::vector<std::pair<std::string, std::string>>& overrides,
                                 [[maybe_unused]] const std::vector<std::pair<std::string, std::string>>& outputs) {
#ifdef STAGGER_WITH_MPI
  const MpiState& state = mpi_state();
  if (!state.active || state.ranks < 2) return;
  const std::uint64_t mine[3] = {digest(scene_text(scene_path)), digest(overrides), digest(outputs)};
  std::vector<std::uint64_t> all(3 * static_cast<std::size_t>(state.ranks));
  MPI_Allgather(mine, 3, MPI_UINT64_T, all.data(), 3, MPI_UINT64_T, MPI_COMM_WORLD);
  std::string outputs_named;
  for (const auto& [key, value] : outputs) outputs_named += (outputs_named.empty() ? "" : ", ") + key;
  const std::string what[3] = {"a scene file whose text differs", "--set values that differ",
                               "output settings (" + outputs_named + ") that differ"};
  for (int r = 1; r < state.ranks; ++r)
    for (int k = 0; k < 3; ++k)
      if (all[3 * static_cast<std::size_t>(r) + k] != all[k])
        throw CollectiveError("rank " + std::to_string(r) + " of " + std::to_string(state.ranks) +
                              " was started with " + what[k] + " from rank 0's (" + scene_path +
                              "); start every rank with the same scene, --set values and options");
#endif
}

Scene load_scene_on_every_rank(const std::string& path,
                               const std::vector<std::pair<std::string, std::string>>& overrides) {
  Scene scene;
#ifdef STAGGER_WITH_MPI
  const MpiState& state = mpi_state();
  if (state.active && state.ranks > 1) {
    on_every_rank([&] {
      if (state.rank == 0) scene = load_scene(path, overrides);
    });
    // The outline: the source, then the region names, then the tag names, each after its
    // length (a count before each list).
    std::string outline;
    const auto put = [&](const std::string& text) {
      const std::uint64_t n = text.size();
      outline.append(reinterpret_cast<const char*>(&n), sizeof n);
      outline += text;
    };
    if (state.rank == 0) {
      const Mesh& m = scene.problem.mesh;
      put(m.source);
      put(std::to_string(m.region_names.size()));
      for (const std::string& name : m.region_names) put(name);
      put(std::to_string(m.tags.size()));
      for (const BoundaryTag& tag : m.tags) put(tag.name);
    }
    std::uint64_t length = outline.size();
    MPI_Bcast(&length, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    outline.resize(length);
    MPI_Bcast(outline.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
    if (state.rank != 0) {
      std::size_t at = 0;
      const auto get = [&] {
        std::uint64_t n = 0;
        std::memcpy(&n, outline.data() + at, sizeof n);
        at += sizeof n;
        std::string text = outline.substr(at, n);
        at += n;
        return text;
      };
      Mesh mesh;
      mesh.source = get();
      mesh.region_names.resize(std::stoul(get()));
      for (std::string& name : mesh.region_names) name = get();
      mesh.tags.resize(std::stoul(get()));
      for (BoundaryTag& tag : mesh.tags) tag.name = get();
      on_every_rank([&] { scene = load_scene_without_mesh(path, overrides, std::move(mesh)); });
    } else {
      on_every_rank([] {});
    }
    return scene;
  }
#endif
  on_every_rank([&] { scene = load_scene(path, overrides); });
  return scene;
}

Simulation distributed_simulation(Problem problem) {
#ifdef STAGGER_WITH_MPI
  if (mpi_state().active) {
    try {
      return distribute(std::move(problem), MPI_COMM_WORLD);
    } catch (const Error& error) {
      throw CollectiveError(error.what());  // distribute's errors are the same on every rank
    }
  }
#endif
  return Simulation(std::move(problem));
}

double peak_resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux: kilobytes
}

void write_rank_statistics([[maybe_unused]] const Simulation& simulation, [[maybe_unused]] const std::string& directory,
                           [[maybe_unused]] double loop_seconds) {
#ifdef STAGGER_WITH_MPI
  if (!mpi_state().active || simulation.ranks() < 2) return;
  const HaloStatistics h = halo_statistics(simulation);
  const std::vector<double> mine = {static_cast<double>(h.owned_zones),
                                    static_cast<double>(h.ghost_zones),
                                    static_cast<double>(h.owned_points),
                                    static_cast<double>(h.ghost_points),
                                    static_cast<double>(h.neighbours),
                                    static_cast<double>(h.exchanges),
                                    static_cast<double>(h.messages),
                                    h.bytes,
                                    h.seconds,
                                    loop_seconds,
                                    peak_resident_bytes()};
  const int ranks = simulation.ranks(), n = static_cast<int>(mine.size());
  std::vector<double> all(static_cast<std::size_t>(n) * ranks);
  MPI_Gather(mine.data(), n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (simulation.rank() != 0) return;
  std::ostringstream out;
  out.precision(17);
  out << "rank,owned_zones,ghost_zones,owned_points,ghost_points,neighbours,exchanges,messages,bytes,halo_seconds,"
         "loop_seconds,cycles,peak_rss_bytes\n";
  for (int r = 0; r < ranks; ++r) {
    out << r;
    for (int k = 0; k + 1 < n; ++k) out << "," << all[static_cast<std::size_t>(r) * n + k];
    out << "," << simulation.cycle() << "," << all[static_cast<std::size_t>(r) * n + n - 1] << "\n";
  }
  write_file_atomically((std::filesystem::path(directory.empty() ? "." : directory) / "ranks.csv").string(), out.str());
#endif
}

}  // namespace stagger::cli
