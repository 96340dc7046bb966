// The physics digest of a checkpoint (physics_digest.hpp).
#include "hydro/physics_digest.hpp"

#include <charconv>
#include <map>
#include <set>
#include <variant>

#include "hydro/boundary_checks.hpp"
#include "stagger/option_table.hpp"
#include "strength/strength_models.hpp"

namespace stagger {

namespace {

using io_detail::fnv1a64;

// Shortest text that reads back as the same double.
std::string number(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::string hex(std::uint64_t hash) {
  static const char* digits = "0123456789abcdef";
  std::string text(16, '0');
  for (int k = 15; k >= 0; --k, hash >>= 4) text[k] = digits[hash & 0xfu];
  return text;
}

// FNV-1a over little-endian encodings of integers and doubles (io/byte_stream.hpp).
class Hasher {
 public:
  void integer(std::int64_t value) { hash_ = fnv1a64(static_cast<std::uint64_t>(value), hash_); }
  void integers(std::span<const Index> values) {
    integer(static_cast<std::int64_t>(values.size()));
    for (const Index v : values) integer(v);
  }
  void value(double v) { hash_ = fnv1a64(std::span<const double>(&v, 1), hash_); }
  void values(std::span<const double> v) {
    integer(static_cast<std::int64_t>(v.size()));
    hash_ = fnv1a64(v, hash_);
  }
  void text(std::string_view t) {
    integer(static_cast<std::int64_t>(t.size()));
    hash_ = fnv1a64(t, hash_);
  }
  std::string digest() const { return hex(hash_); }

 private:
  std::uint64_t hash_ = io_detail::kFnv1aOffset;
};

class Digest {
 public:
  explicit Digest(std::vector<DigestEntry>& entries) : entries_(entries) {}
  void value(const char* section, const std::string& key, const std::string& value) {
    entries_.push_back({section, key, value, false});
  }
  void value(const char* section, const std::string& key, double v) { value(section, key, number(v)); }
  void hashed(const char* section, const std::string& key, const Hasher& h) {
    entries_.push_back({section, key, h.digest(), true});
  }

 private:
  std::vector<DigestEntry>& entries_;
};

void mesh_entries(const Mesh& m, Digest& d) {
  d.value("mesh", "points", static_cast<double>(m.num_points()));
  d.value("mesh", "zones", static_cast<double>(m.num_zones()));
  Hasher coordinates;
  coordinates.values(m.x);
  coordinates.values(m.y);
  d.hashed("mesh", "point coordinates", coordinates);
  Hasher connectivity;
  connectivity.integers(m.zone_corner_begin);
  connectivity.integers(m.corner_point);
  d.hashed("mesh", "zone connectivity", connectivity);
  Hasher regions;
  for (const auto& name : m.region_names) regions.text(name);
  regions.integers(m.zone_region);
  d.hashed("mesh", "zone regions", regions);
  for (const BoundaryTag& tag : m.tags) {
    Hasher h;
    h.integer(static_cast<std::int64_t>(tag.edges.size()));
    for (const auto& e : tag.edges) h.integer(e[0]), h.integer(e[1]);
    h.integers(tag.points);
    d.hashed("mesh", "tag '" + tag.name + "'", h);
  }
}

void material_entries(const Material& mat, Digest& d) {
  const std::string k = mat.name + ".";
  d.value("materials", k + "eos", eos_kind(mat.eos));
  if (const auto* gas = std::get_if<IdealGas>(&mat.eos)) d.value("materials", k + "gamma", gas->gamma);
  if (const auto* mg = std::get_if<MieGruneisen>(&mat.eos)) {
    d.value("materials", k + "rho0", mg->rho0);
    d.value("materials", k + "a0", mg->a0);
    d.value("materials", k + "gamma0", mg->gamma0);
    d.value("materials", k + "s", mg->s);
  }
  if (const auto* jwl = std::get_if<Jwl>(&mat.eos)) {
    d.value("materials", k + "A", jwl->A);
    d.value("materials", k + "B", jwl->B);
    d.value("materials", k + "R1", jwl->R1);
    d.value("materials", k + "R2", jwl->R2);
    d.value("materials", k + "omega", jwl->omega);
    d.value("materials", k + "rho0", jwl->rho0);
  }
  if (const auto* sg = std::get_if<StiffenedGas>(&mat.eos)) {
    d.value("materials", k + "gamma", sg->gamma);
    d.value("materials", k + "p_inf", sg->p_inf);
  }
  d.value("materials", k + "min_energy", mat.min_energy);
  if (mat.strength) {
    // The default model adds no entry, so digests of existing scenes stay as they were.
    if (!is_default_strength_model(*mat.strength))
      d.value("materials", k + "strength.model", strength_model_name(*mat.strength));
    for (const auto& [key, value] : strength_digest_rows(*mat.strength))
      d.value("materials", k + "strength." + key, value);
  } else {
    d.value("materials", k + "strength", "none");
  }
  if (mat.burn) {
    const Burn& b = *mat.burn;
    d.value("materials", k + "burn.detonation_speed", b.detonation_speed);
    Hasher points;
    for (const auto& pt : b.points) points.value(pt[0]), points.value(pt[1]);
    d.hashed("materials", k + "burn.points", points);
    std::string plane = "none";
    if (b.plane) {
      plane.clear();
      for (const double v : *b.plane) {
        if (!plane.empty()) plane += ", ";
        plane += number(v);
      }
    }
    d.value("materials", k + "burn.plane", plane);
    d.value("materials", k + "burn.time_offset", b.time_offset);
    d.value("materials", k + "burn.beta_burn", b.beta_burn ? "true" : "false");
    d.value("materials", k + "burn.cj_relative_volume", b.cj_relative_volume);
  } else {
    d.value("materials", k + "burn", "none");
  }
}

void numerics_entries(const HydroOptions& o, Digest& d) {
  // Every row of the [numerics] option table, so that an option added there is compared too.
  for (const auto& row : numerics_option_table().options) {
    const double v = row.get(o);
    if (row.type == OptionType::number || row.type == OptionType::integer) {
      d.value("numerics", row.key, v);
    } else {
      d.value("numerics", row.key, row.value_text(v));
    }
  }
}

void ale_entries(const AleOptions& o, Digest& d) {
  // Lagrangian scenes keep the digest (and so their checkpoints) of before the [ale] section.
  if (o.mode == AleMode::lagrangian) return;
  for (const auto& row : ale_option_table().options) {
    const double v = row.get(o);
    // A key added later enters the digest only off its default, so older checkpoints restart.
    if (std::string_view(row.key) == "size_weight" && v == 0) continue;
    if (row.type == OptionType::number || row.type == OptionType::integer) {
      d.value("ale", row.key, v);
    } else {
      d.value("ale", row.key, row.value_text(v));
    }
  }
}

// Keys are unique within a section (a repeated one gets " #2", " #3", ...).
void make_keys_unique(std::vector<DigestEntry>& entries) {
  std::map<std::pair<std::string, std::string>, int> seen;
  for (auto& e : entries) {
    const int n = ++seen[{e.section, e.key}];
    if (n > 1) e.key += " #" + std::to_string(n);
  }
}

}  // namespace

std::vector<DigestEntry> setup_digest(const Simulation::Impl& s) {
  const Problem& problem = s.problem;
  const Mesh& m = s.mesh();
  std::vector<DigestEntry> entries;
  Digest d(entries);
  mesh_entries(m, d);
  for (const Material& mat : problem.materials) material_entries(mat, d);
  // The regions' initial state as the set-up made it from their functions.
  for (const RegionSetup& setup : problem.regions) {
    const int r = m.region_index(setup.region);
    const Index z0 = m.region_zone_begin[r], z1 = m.region_zone_begin[r + 1];
    const std::string k = setup.region + ".";
    d.value("regions", k + "material", setup.material);
    Hasher mass, energy, velocity, stress;
    mass.values(std::span(s.zone_mass).subspan(z0, z1 - z0));
    energy.values(std::span(s.e).subspan(z0, z1 - z0));
    for (Index c = m.zone_corner_begin[z0]; c < m.zone_corner_begin[z1]; ++c) {
      velocity.value(s.vx[m.corner_point[c]]);
      velocity.value(s.vy[m.corner_point[c]]);
    }
    d.hashed("regions", k + "density", mass);
    d.hashed("regions", k + "energy", energy);
    d.hashed("regions", k + "velocity", velocity);
    if (s.any_strength) {
      for (const auto* v : {&s.sxx, &s.syy, &s.sxy}) stress.values(std::span(*v).subspan(z0, z1 - z0));
      d.hashed("regions", k + "stress", stress);
    }
  }
  for (const BoundaryCondition& bc : problem.boundaries) {
    d.value("boundaries", bc.tag + ".type", boundary_kind_name(bc.kind));
    if (bc.kind == BoundaryKind::periodic) d.value("boundaries", bc.tag + ".partner", bc.partner);
  }
  for (std::size_t i = 0; i < problem.deposits.size(); ++i) {
    const EnergyDeposit& dep = problem.deposits[i];
    std::string where = "deposit[";
    where += std::to_string(i);
    where += "]";
    std::string what = "energy ";
    what += number(dep.energy);
    what += " at (";
    what += number(dep.x);
    what += ", ";
    what += number(dep.y);
    what += ")";
    d.value("sources", where, what);
  }
  d.value("sources", "manufactured", problem.sources ? "on" : "off");
  numerics_entries(problem.options, d);
  ale_entries(problem.ale, d);
  make_keys_unique(entries);
  return entries;
}

std::vector<DigestEntry> sampled_digest(const Simulation::Impl& s, double t_reference) {
  constexpr int kSamples = 16;
  const Problem& problem = s.problem;
  std::vector<DigestEntry> entries;
  Digest d(entries);
  auto sample_time = [&](int k) { return t_reference * k / kSamples; };
  for (const BoundaryCondition& bc : problem.boundaries) {
    if (bc.kind == BoundaryKind::velocity) {
      Hasher h;
      for (int k = 0; k <= kSamples; ++k)
        h.value(bc.velocity_x(sample_time(k))), h.value(bc.velocity_y(sample_time(k)));
      d.hashed("boundaries", bc.tag + ".velocity", h);
    }
    if (bc.kind == BoundaryKind::pressure ||
        (bc.kind == BoundaryKind::transmitting && !bc.far_field_from_initial_state)) {
      Hasher h;
      for (int k = 0; k <= kSamples; ++k) h.value(bc.pressure(sample_time(k)));
      d.hashed("boundaries", bc.tag + ".pressure", h);
    }
  }
  if (problem.sources) {
    // At three points of the initial mesh (first, middle, last).
    const Mesh& m = s.mesh();
    const Index np = m.num_points();
    const Index points[3] = {0, np / 2, np - 1};
    Hasher momentum, energy;
    for (int k = 0; k <= kSamples; ++k)
      for (const Index p : points) {
        if (problem.sources->momentum) {
          const auto f = problem.sources->momentum(m.x[p], m.y[p], sample_time(k));
          momentum.value(f[0]), momentum.value(f[1]);
        }
        if (problem.sources->energy) energy.value(problem.sources->energy(m.x[p], m.y[p], sample_time(k)));
      }
    d.hashed("sources", "momentum", momentum);
    d.hashed("sources", "energy", energy);
  }
  make_keys_unique(entries);
  return entries;
}

void write_digest(io_detail::ByteWriter& out, const std::vector<DigestEntry>& digest) {
  out.u64(digest.size());
  for (const auto& e : digest) {
    out.bytes(e.section);
    out.bytes(e.key);
    out.bytes(e.value);
    out.u8(e.hashed ? 1 : 0);
  }
}

std::vector<DigestEntry> read_digest(io_detail::ByteReader& in) {
  // An entry takes at least 25 bytes: three string lengths and the flag.
  std::vector<DigestEntry> digest(in.count(25, "physics digest entries"));
  for (auto& e : digest) {
    e.section = in.bytes();
    e.key = in.bytes();
    e.value = in.bytes();
    e.hashed = in.u8() != 0;
  }
  return digest;
}

std::string digest_differences(const std::vector<DigestEntry>& saved, const std::vector<DigestEntry>& current) {
  using Key = std::pair<std::string, std::string>;
  std::map<Key, const DigestEntry*> now;
  for (const auto& e : current) now[{e.section, e.key}] = &e;
  std::vector<std::string> lines;
  std::set<Key> matched;
  for (const auto& e : saved) {
    const Key key{e.section, e.key};
    const auto it = now.find(key);
    if (it == now.end()) {
      lines.push_back(e.section + ": " + e.key + (e.hashed ? " is gone" : " was " + e.value + ", now absent"));
      continue;
    }
    matched.insert(key);
    const DigestEntry& c = *it->second;
    if (c.value == e.value) continue;
    lines.push_back(e.section + ": " + e.key +
                    (e.hashed || c.hashed ? " differs" : " was " + e.value + ", now " + c.value));
  }
  for (const auto& c : current) {
    if (matched.count({c.section, c.key})) continue;
    lines.push_back(c.section + ": " + c.key + (c.hashed ? " is new" : " is new (" + c.value + ")"));
  }
  std::string text;
  constexpr std::size_t kShown = 12;
  for (std::size_t i = 0; i < lines.size() && i < kShown; ++i) {
    if (i > 0) text += "; ";
    text += lines[i];
  }
  if (lines.size() > kShown) text += "; and " + std::to_string(lines.size() - kShown) + " more";
  return text;
}

}  // namespace stagger
