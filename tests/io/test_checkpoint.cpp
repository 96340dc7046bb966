// Checkpoints that cannot lie (docs/output.md, "Checkpoints"): the file format as documented,
// a checksum that catches any flipped bit, a physics digest that refuses a restart with
// other physics and names what differs, and an end time that must lie after the checkpoint.
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>

#include "io_test_support.hpp"
#include "stagger/error.hpp"
#include "stagger/output.hpp"
#include "stagger/run.hpp"
#include "stagger/simulation.hpp"

namespace stagger {
namespace {

using io_test::read_text;
using io_test::ScratchDirectory;

// FNV-1a 64 written from its definition, independently of the library's.
std::uint64_t fnv1a(std::string_view data) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : data) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

std::uint64_t little_endian_u64(std::string_view bytes) {
  std::uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[k])) << (8 * k);
  return v;
}

RunControl control_in(const ScratchDirectory& scratch, const std::string& sub) {
  RunControl control;
  control.output_directory = (scratch.path() / sub).string();
  control.name = "sod";
  control.progress = false;
  control.dumps = false;
  control.checkpoint_every_cycles = 5;
  control.checkpoint_every_seconds = 0;
  return control;
}

// Runs the small Sod problem to t_end with checkpoints every 5 cycles; returns the path of
// the checkpoint of cycle 10 (set aside as the run goes) and its time.
std::pair<std::string, double> checkpoint_of_cycle_10(const ScratchDirectory& scratch, Problem problem) {
  const RunControl control = control_in(scratch, "original");
  const std::string saved = scratch.file("cycle10.checkpoint");
  double t10 = -1;
  Simulation simulation(std::move(problem));
  simulation.set_observer([&](const Simulation& s) {
    if (s.cycle() == 10) t10 = s.time();
    if (s.cycle() == 11) std::filesystem::copy_file(control.output_directory + "/sod.checkpoint", saved);
  });
  const RunResult result = run(simulation, control);
  EXPECT_TRUE(result.completed) << result.message;
  EXPECT_GT(simulation.cycle(), 11);
  return {saved, t10};
}

// The message of the Error that resuming `problem` from `checkpoint` throws ("" if none).
std::string resume_error(const ScratchDirectory& scratch, Problem problem, const std::string& checkpoint) {
  Simulation simulation(std::move(problem));
  try {
    resume(simulation, control_in(scratch, "resumed"), checkpoint);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Checkpoint, OwnFnvMatchesTheReferenceVectors) {
  EXPECT_EQ(fnv1a(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a("foobar"), 0x85944171f73967e8ull);
}

TEST(Checkpoint, FileIsTheDocumentedFormat) {
  ScratchDirectory scratch("ckpt_format");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  const std::string data = read_text(path);
  const std::string_view magic = "stagger checkpoint\n";
  ASSERT_GT(data.size(), magic.size() + 16);
  EXPECT_EQ(data.substr(0, magic.size()), magic);
  EXPECT_EQ(little_endian_u64(std::string_view(data).substr(magic.size(), 8)), 2u) << "format version";
  // Then the scene name, length-prefixed.
  const std::uint64_t name_length = little_endian_u64(std::string_view(data).substr(magic.size() + 8, 8));
  EXPECT_EQ(data.substr(magic.size() + 16, name_length), "sod_io");
  // The last 8 bytes: FNV-1a 64 of every byte before them.
  const std::string_view payload = std::string_view(data).substr(0, data.size() - 8);
  EXPECT_EQ(little_endian_u64(std::string_view(data).substr(data.size() - 8)), fnv1a(payload));
  EXPECT_GT(t10, 0);
}

TEST(Checkpoint, AnyFlippedBitIsDetectedAndTheFileNamed) {
  ScratchDirectory scratch("ckpt_flip");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  const std::string good = read_text(path);
  const std::string flipped = scratch.file("flipped.checkpoint");
  // One bit in each of ~150 bytes spread over the file, the checksum itself included, a
  // different bit each time.
  const std::size_t stride = std::max<std::size_t>(1, good.size() / 150);
  int tried = 0;
  for (std::size_t i = 0; i < good.size(); i += stride, ++tried) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ (1 << (tried % 8)));
    write_file_atomically(flipped, bad);
    const std::string message = resume_error(scratch, io_test::sod_problem(40, 0.1), flipped);
    ASSERT_FALSE(message.empty()) << "a flipped bit at byte " << i << " of " << good.size() << " went unnoticed";
    EXPECT_TRUE(contains(message, "flipped.checkpoint")) << message;
    if (i >= 19 + 8) {  // past the header and the version: the checksum catches it
      EXPECT_TRUE(contains(message, "checksum")) << "byte " << i << ": " << message;
    }
  }
  EXPECT_GT(tried, 100);
  // The intact file still resumes.
  EXPECT_EQ(resume_error(scratch, io_test::sod_problem(40, 0.1), path), "");
}

// A checkpoint with a valid checksum but driver fields no run writes (a crafted file): each is
// refused, naming the field, before anything reaches the new run's files.
TEST(Checkpoint, CraftedDriverFieldsWithAValidChecksumAreRefused) {
  ScratchDirectory scratch("ckpt_crafted");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  const std::string good = read_text(path);
  const std::size_t magic = 19;
  const std::size_t fields = magic + 16 + little_endian_u64(std::string_view(good).substr(magic + 8, 8));
  auto put_u64 = [](std::string& data, std::size_t at, std::uint64_t value) {
    for (int k = 0; k < 8; ++k) data[at + k] = static_cast<char>((value >> (8 * k)) & 0xffu);
  };
  auto reseal = [&](std::string data) {
    data.resize(data.size() - 8);
    const std::uint64_t sum = fnv1a(data);
    data.append(8, '\0');
    put_u64(data, data.size() - 8, sum);
    return data;
  };
  auto message_for = [&](const std::string& data) {
    const std::string crafted = scratch.file("crafted.checkpoint");
    write_file_atomically(crafted, reseal(data));
    return resume_error(scratch, io_test::sod_problem(40, 0.1), crafted);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string bad = good;
  std::uint64_t bits;
  std::memcpy(&bits, &nan, 8);
  put_u64(bad, fields, bits);  // next dump time
  EXPECT_TRUE(contains(message_for(bad), "impossible next dump time")) << message_for(bad);
  bad = good;
  put_u64(bad, fields + 16, static_cast<std::uint64_t>(-5));  // dump count
  EXPECT_TRUE(contains(message_for(bad), "impossible dump count")) << message_for(bad);
  // A .pvd entry that climbs out of the output directory: count 1, dump count 1.
  bad = good;
  put_u64(bad, fields + 16, 1);
  put_u64(bad, fields + 56, 1);
  std::string entry(8, '\0');
  std::memcpy(entry.data(), &t10, 8);
  const std::string climb = "../../../../etc/passwd";
  entry.append(8, '\0');
  put_u64(entry, 8, climb.size());
  entry += climb;
  bad.insert(fields + 64, entry);
  EXPECT_TRUE(contains(message_for(bad), "impossible .pvd entry '../../../../etc/passwd'")) << message_for(bad);
  // History rows that are not numbers.
  bad = good;
  const std::size_t history = fields + 64;
  const std::uint64_t length = little_endian_u64(std::string_view(bad).substr(history, 8));
  bad[history + 8 + length - 3] = '<';
  EXPECT_TRUE(contains(message_for(bad), "impossible history table")) << message_for(bad);
  EXPECT_EQ(message_for(good), "");  // resealing alone changes nothing
}

TEST(Checkpoint, ChangedGammaIsRefusedAndNamed) {
  ScratchDirectory scratch("ckpt_gamma");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  Problem other = io_test::sod_problem(40, 0.1);
  other.materials[0].eos = IdealGas{5.0 / 3.0};
  const std::string message = resume_error(scratch, std::move(other), path);
  EXPECT_TRUE(contains(message, "cycle10.checkpoint")) << message;
  EXPECT_TRUE(contains(message, "materials: gas.gamma was 1.4, now 1.6666666666666667")) << message;
  // The same pressure with another gamma is another initial energy: also named.
  EXPECT_TRUE(contains(message, "regions: domain.energy differs")) << message;
  EXPECT_TRUE(contains(message, "a restart may change only the end time and the output settings")) << message;
}

TEST(Checkpoint, ChangedDensityIsRefusedAndNamed) {
  ScratchDirectory scratch("ckpt_density");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  Problem other = io_test::sod_problem(40, 0.1);
  other.regions[0].density = [](double x, double) { return x < 0.5 ? 1.0 : 0.25; };
  const std::string message = resume_error(scratch, std::move(other), path);
  EXPECT_TRUE(contains(message, "regions: domain.density differs")) << message;
  EXPECT_FALSE(contains(message, "materials")) << message;
}

TEST(Checkpoint, ChangedNumericsBoundariesAndMeshAreNamed) {
  ScratchDirectory scratch("ckpt_other");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  Problem numerics = io_test::sod_problem(40, 0.1);
  numerics.options.cfl = 0.3;
  EXPECT_TRUE(contains(resume_error(scratch, std::move(numerics), path), "numerics: cfl was 0.15, now 0.3"));
  Problem boundary = io_test::sod_problem(40, 0.1);
  boundary.boundaries[1].kind = BoundaryKind::free;
  EXPECT_TRUE(contains(resume_error(scratch, std::move(boundary), path), "boundaries: right.type was wall, now free"));
  const std::string mesh = resume_error(scratch, io_test::sod_problem(42, 0.1), path);
  EXPECT_TRUE(contains(mesh, "mesh: points was 82, now 86")) << mesh;
}

TEST(Checkpoint, EndTimeAtOrBeforeTheCheckpointIsRefused) {
  ScratchDirectory scratch("ckpt_end");
  const auto [path, t10] = checkpoint_of_cycle_10(scratch, io_test::sod_problem(40, 0.1));
  ASSERT_GT(t10, 0);
  for (const double t_end : {0.5 * t10, t10}) {
    const std::string message = resume_error(scratch, io_test::sod_problem(40, t_end), path);
    EXPECT_TRUE(contains(message, "cycle10.checkpoint")) << message;
    EXPECT_TRUE(contains(message, "a restart needs a later end time")) << "t_end " << t_end << ": " << message;
  }
  // A later end time (shorter or longer than the original run) is what restarts are for.
  for (const double t_end : {1.5 * t10, 0.15}) {
    Simulation simulation(io_test::sod_problem(40, t_end));
    const RunResult result = resume(simulation, control_in(scratch, "later"), path);
    EXPECT_TRUE(result.completed) << result.message;
    EXPECT_EQ(simulation.time(), t_end);
  }
}

TEST(Checkpoint, EarlierFormatVersionIsNamed) {
  ScratchDirectory scratch("ckpt_version");
  std::string old = "stagger checkpoint\n";
  old += std::string("\x01\0\0\0\0\0\0\0", 8);
  old += std::string(64, 'x');
  write_file_atomically(scratch.file("old.checkpoint"), old);
  const std::string message = resume_error(scratch, io_test::sod_problem(40, 0.1), scratch.file("old.checkpoint"));
  EXPECT_TRUE(contains(message, "old.checkpoint")) << message;
  EXPECT_TRUE(contains(message, "format version 1, this build reads version 2")) << message;
}

TEST(Checkpoint, SimulationBlobRestoresBitwiseAndRefusesOtherPhysics) {
  Simulation a(io_test::sod_problem(40, 0.1));
  a.advance_to(0.03);
  const std::string blob = a.checkpoint();
  Simulation b(io_test::sod_problem(40, 0.2));  // another end time: allowed
  b.restore(blob);
  a.advance_to(0.06);
  b.advance_to(0.06);
  ASSERT_EQ(a.cycle(), b.cycle());
  EXPECT_EQ(std::memcmp(a.x().data(), b.x().data(), a.x().size_bytes()), 0);
  EXPECT_EQ(std::memcmp(a.specific_internal_energy().data(), b.specific_internal_energy().data(),
                        a.specific_internal_energy().size_bytes()),
            0);

  // A crafted count (the checksum of a file would not catch a deliberate one) is an error, not
  // an allocation of its size.
  std::string crafted = blob;
  crafted.replace(8, 8, std::string("\0\0\0\0\0\0\0\x10", 8));  // 2^60 digest entries
  try {
    b.restore(crafted, "crafted");
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_TRUE(contains(error.what(), "crafted: is corrupt")) << error.what();
  }

  Problem hotter = io_test::sod_problem(40, 0.1);
  hotter.regions[0].pressure = [](double x, double) { return x < 0.5 ? 2.0 : 0.1; };
  Simulation c(std::move(hotter));
  const auto before = std::vector<double>(c.specific_internal_energy().begin(), c.specific_internal_energy().end());
  try {
    c.restore(blob, "snapshot 7");
    FAIL() << "expected stagger::Error";
  } catch (const Error& error) {
    EXPECT_TRUE(contains(error.what(), "snapshot 7")) << error.what();
    EXPECT_TRUE(contains(error.what(), "regions: domain.energy differs")) << error.what();
  }
  // A refused restore leaves the state as it was.
  EXPECT_EQ(c.time(), 0.0);
  EXPECT_EQ(std::vector<double>(c.specific_internal_energy().begin(), c.specific_internal_energy().end()), before);
}

}  // namespace
}  // namespace stagger
