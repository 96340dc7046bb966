// stagger::Simulation: the running problem, which composes the phases (the Lagrangian step
// of hydro/, the built-in ALE of ale/ behind the public remap door, a distributed run's
// collective), and its public face: state views, diagnostics, checkpoints.
#include "stagger/simulation.hpp"

#include <cmath>

#include "ale/ale_remap.hpp"
#include "hydro/collective.hpp"
#include "hydro/exact_sum.hpp"
#include "hydro/physics_digest.hpp"
#include "hydro/simulation_impl.hpp"
#include "io/byte_stream.hpp"
#include "stagger/error.hpp"
#include "state/state_table.hpp"

namespace stagger {

Simulation::Simulation(Problem problem, LagrangianOnly) : impl_(std::make_unique<Impl>(std::move(problem))) {
  impl_->owner = this;
}
Simulation::Simulation(Problem problem) : Simulation(std::move(problem), LagrangianOnly{}) {
  // ale.mode other than "lagrangian": the built-in ALE phase behind the remap door (docs/ale.md).
  if (impl_->ale) impl_->remap = make_ale_remap(*impl_);
}
Simulation::~Simulation() = default;
Simulation::Impl::~Impl() = default;
// The observer is handed the owning Simulation: keep the back pointer right across moves.
Simulation::Simulation(Simulation&& other) noexcept : impl_(std::move(other.impl_)) {
  if (impl_) impl_->owner = this;
}
Simulation& Simulation::operator=(Simulation&& other) noexcept {
  impl_ = std::move(other.impl_);
  if (impl_) impl_->owner = this;
  return *this;
}

void Simulation::step(double t_stop) {
  impl_->step(t_stop < 0 ? impl_->problem.t_end : t_stop);
}

void Simulation::advance_to(double t) {
  while (impl_->t < t) impl_->step(t);
}

bool Simulation::finished() const {
  return impl_->t >= impl_->problem.t_end;
}
double Simulation::time() const {
  return impl_->t;
}
long Simulation::cycle() const {
  return impl_->cycle;
}
double Simulation::dt() const {
  return impl_->dt_last;
}

std::string Simulation::dt_limit() const {
  using R = Impl::DtReason;
  switch (impl_->dt_reason) {
    case R::cfl:
      return "cfl/volume limit of zone " + std::to_string(impl_->dt_zone);
    case R::growth:
      return "growth limit";
    case R::initial:
      return "dt_init";
    case R::maximum:
      return "dt_max";
    case R::retry:
      return "retry after a tangled step";
    case R::landing:
      return "landing on an output or end time";
    case R::heat_flux:
      return "heat-flux limit of zone " + std::to_string(impl_->dt_zone);
  }
  return "";
}

const Problem& Simulation::problem() const {
  return impl_->problem;
}
const Mesh& Simulation::mesh() const {
  return impl_->mesh();
}

std::span<const double> Simulation::x() const {
  return impl_->x;
}
std::span<const double> Simulation::y() const {
  return impl_->y;
}
std::span<const double> Simulation::velocity_x() const {
  return impl_->vx;
}
std::span<const double> Simulation::velocity_y() const {
  return impl_->vy;
}
std::span<const double> Simulation::point_mass() const {
  return impl_->point_mass;
}
std::span<const double> Simulation::zone_mass() const {
  return impl_->zone_mass;
}
std::span<const double> Simulation::zone_area() const {
  return impl_->area;
}
std::span<const double> Simulation::density() const {
  return impl_->rho;
}
std::span<const double> Simulation::pressure() const {
  return impl_->p;
}
std::span<const double> Simulation::specific_internal_energy() const {
  return impl_->e;
}
std::span<const double> Simulation::artificial_viscosity() const {
  return impl_->q;
}
std::span<const double> Simulation::sound_speed() const {
  return impl_->c;
}
bool Simulation::has_strength() const {
  return impl_->any_strength;
}
std::span<const double> Simulation::stress_xx() const {
  return impl_->sxx;
}
std::span<const double> Simulation::stress_yy() const {
  return impl_->syy;
}
std::span<const double> Simulation::stress_xy() const {
  return impl_->sxy;
}
std::span<const double> Simulation::plastic_strain() const {
  return impl_->plastic;
}
bool Simulation::has_burn() const {
  return impl_->any_burn;
}
std::span<const double> Simulation::burn_fraction() const {
  return impl_->burn;
}

EnergyAudit Simulation::energy() const {
  EnergyAudit a;
  a.kinetic = impl_->kinetic_energy();
  a.internal = impl_->internal_energy();
  a.total = a.kinetic + a.internal;
  a.initial = impl_->energy_initial;
  a.boundary_work = impl_->boundary_work;
  a.source_work = impl_->source_work;
  a.ale_fixup = impl_->ale_fixup;
  const double w = a.boundary_work + a.source_work;
  // docs/algorithm.md §11: normalise by max(E0, |W|, E), not E0 alone (E0 is 40x smaller than W on the piston).
  const double scale = std::max({std::abs(a.initial), std::abs(w), std::abs(a.total)});
  a.relative_error = scale > 0 ? (a.total - a.initial - w) / scale : 0.0;
  return a;
}

std::array<double, 2> Simulation::momentum() const {
  // Exact sums over this rank's own points (docs/parallel.md, "Determinism").
  const Impl& s = *impl_;
  std::array<ExactSum, 2> sums;
  for (std::size_t p = 0; p < s.vx.size(); ++p) {
    if (!s.ghost_point.empty() && s.ghost_point[p]) continue;
    sums[0].add(s.point_mass[p] * s.vx[p]);
    sums[1].add(s.point_mass[p] * s.vy[p]);
  }
  if (s.collective) s.collective->sum(sums);
  return {sums[0].value(), sums[1].value()};
}

int Simulation::rank() const {
  return impl_->collective ? impl_->collective->rank() : 0;
}
int Simulation::ranks() const {
  return impl_->collective ? impl_->collective->ranks() : 1;
}
const Simulation* Simulation::gather() const {
  return impl_->collective ? impl_->collective->gather(*impl_) : this;
}
std::span<const Index> Simulation::global_zones() const {
  return impl_->global_zone;
}
std::span<const Index> Simulation::global_points() const {
  return impl_->global_point;
}
std::span<const unsigned char> Simulation::ghost_zones() const {
  return impl_->ghost_zone;
}
std::string Simulation::agree(const std::string& text) const {
  return impl_->collective ? impl_->collective->agree(text) : text;
}
bool Simulation::any_rank(bool local) const {
  return impl_->collective ? impl_->collective->any(local) : local;
}

void Simulation::set_remap(std::shared_ptr<Remap> remap) {
  impl_->remap = std::move(remap);
}

void Simulation::set_observer(std::function<void(const Simulation&)> observer) {
  impl_->observer = std::move(observer);
}

std::vector<Simulation::OutputField> Simulation::output_fields() const {
  std::vector<OutputField> fields;
  for (const StateField& f : state_fields()) {
    if (!(f.flags & kDumped) || !present(*impl_, f.presence)) continue;
    fields.push_back(
        {f.output_name, f.entity == Entity::point, f.presence == Presence::always, f.output_role, (*impl_).*f.member});
  }
  return fields;
}

// ---- checkpoints: the state table's checkpointed arrays in the binary format of
// io/byte_stream.hpp, behind the physics digest (docs/output.md, "Checkpoints") ----
namespace {
constexpr std::string_view kBlobMagic = "STGCKPT5";  // the last character is the blob's version
}  // namespace

std::string Simulation::checkpoint() const {
  const Impl& s = *impl_;
  io_detail::ByteWriter w;
  w.raw(kBlobMagic);
  write_digest(w, s.digest);
  w.f64(s.problem.t_end);  // the functions of time are sampled in [0, t_end]
  write_digest(w, sampled_digest(s, s.problem.t_end));
  write_clock(w, s);
  for (const StateField& f : state_fields()) {
    if (!(f.flags & kCheckpointed)) continue;
    w.bytes(f.name);
    w.doubles(s.*f.member);  // empty when absent
  }
  return w.take();
}

namespace {

// The checks of a state blob (magic, physics digest, every array's name and size); returns its
// clock and leaves `arrays` at the first array.
Clock checked_blob(const Simulation::Impl& s, std::string_view blob, const std::string& source,
                   io_detail::ByteReader& arrays) {
  io_detail::ByteReader r(blob, source);
  if (blob.size() < kBlobMagic.size() || !r.raw_equals(kBlobMagic)) {
    if (blob.substr(0, kBlobMagic.size() - 1) == kBlobMagic.substr(0, kBlobMagic.size() - 1))
      r.fail("holds a simulation state of another format version; this build reads version " +
             std::string(1, kBlobMagic.back()) + ": restart from t = 0");
    r.fail("is not a Stagger simulation state (bad magic number)");
  }
  // The physics first: a checkpoint of other physics would "continue" a different problem.
  std::vector<DigestEntry> saved = read_digest(r);
  const double t_reference = r.f64();
  std::vector<DigestEntry> saved_sampled = read_digest(r);
  saved.insert(saved.end(), saved_sampled.begin(), saved_sampled.end());
  std::vector<DigestEntry> current = s.digest;
  const std::vector<DigestEntry> current_sampled = sampled_digest(s, t_reference);
  current.insert(current.end(), current_sampled.begin(), current_sampled.end());
  if (const std::string differences = digest_differences(saved, current); !differences.empty()) {
    r.fail("was written for other physics than this scene's: " + differences +
           " (a restart may change only the end time and the output settings)");
  }
  const Clock clock = read_clock(r);
  // Two passes over the arrays: check every name and size, then copy, so that a bad blob
  // leaves the state untouched.
  arrays = r;
  for (const StateField& f : state_fields()) {
    if (!(f.flags & kCheckpointed)) continue;
    if (r.bytes_view() != f.name) r.fail(std::string("is corrupt: expected the field '") + f.name + "'");
    const std::size_t expected = (s.*f.member).size();
    if (const std::uint64_t count = r.skip_doubles(); count != expected) {
      r.fail(std::string("field '") + f.name + "' has " + std::to_string(count) + " values, this problem has " +
             std::to_string(expected));
    }
  }
  r.expect_end();
  return clock;
}

}  // namespace

void Simulation::restore(std::string_view blob, const std::string& source) {
  // Every check before any change and before any collective; in a distributed run the ranks
  // then agree, so a bad piece on one rank (another rank's, another set's) stops every rank with
  // its message instead of leaving the others alone in the collectives of recompute_state.
  std::string problem;
  Clock clock;
  io_detail::ByteReader arrays(blob, source);
  try {
    clock = checked_blob(*impl_, blob, source, arrays);
  } catch (const Error& e) {
    problem = e.what();
  }
  if (problem = agree(problem); !problem.empty()) throw Error(problem);
  Impl& s = *impl_;
  for (const StateField& f : state_fields()) {
    if (!(f.flags & kCheckpointed)) continue;
    arrays.bytes_view();
    arrays.doubles(s.*f.member, f.name);
  }
  // recompute_state() sets the next step's dt candidate from the state: the saved one wins.
  static_cast<Clock&>(s) = clock;
  if (s.rz && !s.ale_corner_mass.empty()) ale_axis_masses(s);  // from the restored subcell masses
  s.recompute_state();
  s.dt_next = clock.dt_next;
  s.dt_zone = clock.dt_zone;
}

}  // namespace stagger
