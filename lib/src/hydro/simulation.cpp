// stagger::Simulation: the public face of the Lagrangian phase (state views, diagnostics,
// checkpoints). The step itself is in step.cpp, the set-up in setup.cpp.
#include "stagger/simulation.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

#include "hydro/simulation_impl.hpp"
#include "stagger/error.hpp"

namespace stagger {

Simulation::Simulation(Problem problem) : impl_(std::make_unique<Impl>(std::move(problem))) { impl_->owner = this; }
Simulation::~Simulation() = default;
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

bool Simulation::finished() const { return impl_->t >= impl_->problem.t_end; }
double Simulation::time() const { return impl_->t; }
long Simulation::cycle() const { return impl_->cycle; }
double Simulation::dt() const { return impl_->dt_last; }

std::string Simulation::dt_limit() const {
  using R = Impl::DtReason;
  switch (impl_->dt_reason) {
    case R::cfl: return "cfl/volume limit of zone " + std::to_string(impl_->dt_zone);
    case R::growth: return "growth limit";
    case R::initial: return "dt_init";
    case R::maximum: return "dt_max";
    case R::retry: return "retry after a tangled step";
    case R::landing: return "landing on an output or end time";
  }
  return "";
}

const Problem& Simulation::problem() const { return impl_->problem; }
const Mesh& Simulation::mesh() const { return impl_->mesh(); }

std::span<const double> Simulation::x() const { return impl_->x; }
std::span<const double> Simulation::y() const { return impl_->y; }
std::span<const double> Simulation::velocity_x() const { return impl_->vx; }
std::span<const double> Simulation::velocity_y() const { return impl_->vy; }
std::span<const double> Simulation::point_mass() const { return impl_->point_mass; }
std::span<const double> Simulation::zone_mass() const { return impl_->zone_mass; }
std::span<const double> Simulation::zone_area() const { return impl_->area; }
std::span<const double> Simulation::density() const { return impl_->rho; }
std::span<const double> Simulation::pressure() const { return impl_->p; }
std::span<const double> Simulation::specific_internal_energy() const { return impl_->e; }
std::span<const double> Simulation::artificial_viscosity() const { return impl_->q; }
std::span<const double> Simulation::sound_speed() const { return impl_->c; }
bool Simulation::has_strength() const { return impl_->any_strength; }
std::span<const double> Simulation::stress_xx() const { return impl_->sxx; }
std::span<const double> Simulation::stress_yy() const { return impl_->syy; }
std::span<const double> Simulation::stress_xy() const { return impl_->sxy; }
std::span<const double> Simulation::plastic_strain() const { return impl_->plastic; }
bool Simulation::has_burn() const { return impl_->any_burn; }
std::span<const double> Simulation::burn_fraction() const { return impl_->burn; }

EnergyAudit Simulation::energy() const {
  EnergyAudit a;
  a.kinetic = impl_->kinetic_energy();
  a.internal = impl_->internal_energy();
  a.total = a.kinetic + a.internal;
  a.initial = impl_->energy_initial;
  a.boundary_work = impl_->boundary_work;
  a.source_work = impl_->source_work;
  const double w = a.boundary_work + a.source_work;
  // NUMERICS section 9: normalise by max(E0, |W|, E), not E0 alone.
  const double scale = std::max({std::abs(a.initial), std::abs(w), std::abs(a.total)});
  a.relative_error = scale > 0 ? (a.total - a.initial - w) / scale : 0.0;
  return a;
}

std::array<double, 2> Simulation::momentum() const {
  std::array<double, 2> m{0, 0};
  for (std::size_t p = 0; p < impl_->vx.size(); ++p) {
    m[0] += impl_->point_mass[p] * impl_->vx[p];
    m[1] += impl_->point_mass[p] * impl_->vy[p];
  }
  return m;
}

void Simulation::set_remap(std::shared_ptr<Remap> remap) { impl_->remap = std::move(remap); }

void Simulation::set_observer(std::function<void(const Simulation&)> observer) {
  impl_->observer = std::move(observer);
}

// ---- checkpoints: a flat binary blob, versioned, checked against the mesh ----
namespace {
constexpr char kMagic[8] = {'S', 'T', 'G', 'C', 'K', 'P', 'T', '1'};

struct Writer {
  std::string out;
  template <class T>
  void value(const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void array(const std::vector<double>& v) {
    value<std::uint64_t>(v.size());
    if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
};

struct Reader {
  std::string_view in;
  std::size_t pos = 0;
  template <class T>
  T value() {
    if (pos + sizeof(T) > in.size()) throw Error("checkpoint is truncated");
    T v;
    std::memcpy(&v, in.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  void array(std::vector<double>& v, const char* name) {
    const auto n = value<std::uint64_t>();
    if (n != v.size()) {
      std::ostringstream msg;
      msg << "checkpoint does not match this problem: field '" << name << "' has " << n << " values, expected "
          << v.size();
      throw Error(msg.str());
    }
    if (pos + n * sizeof(double) > in.size()) throw Error("checkpoint is truncated");
    if (n > 0) std::memcpy(v.data(), in.data() + pos, n * sizeof(double));  // empty fields: no pointer
    pos += n * sizeof(double);
  }
};
}  // namespace

std::string Simulation::checkpoint() const {
  const Impl& s = *impl_;
  Writer w;
  w.out.append(kMagic, sizeof(kMagic));
  w.value<std::int64_t>(s.mesh().num_points());
  w.value<std::int64_t>(s.mesh().num_zones());
  w.value(s.t);
  w.value(s.dt_last);
  w.value(s.dt_next);
  w.value(s.dt_control_prev);
  w.value<std::int64_t>(s.cycle);
  w.value<std::int64_t>(s.dt_zone);
  w.value<std::uint8_t>(s.have_previous_forces ? 1 : 0);
  w.value(s.energy_initial);
  w.value(s.boundary_work);
  w.value(s.source_work);
  for (const auto* v : {&s.x, &s.y, &s.vx, &s.vy, &s.e, &s.q, &s.corner_fx, &s.corner_fy, &s.sxx, &s.syy, &s.sxy,
                        &s.plastic, &s.burn})
    w.array(*v);
  return w.out;
}

void Simulation::restore(std::string_view blob) {
  Impl& s = *impl_;
  if (blob.size() < sizeof(kMagic) || std::memcmp(blob.data(), kMagic, sizeof(kMagic)) != 0)
    throw Error("not a Stagger checkpoint (bad magic number)");
  Reader r{blob, sizeof(kMagic)};
  const auto np = r.value<std::int64_t>(), nz = r.value<std::int64_t>();
  if (np != s.mesh().num_points() || nz != s.mesh().num_zones()) {
    std::ostringstream msg;
    msg << "checkpoint is for a mesh of " << np << " points and " << nz << " zones; this problem has "
        << s.mesh().num_points() << " and " << s.mesh().num_zones();
    throw Error(msg.str());
  }
  s.t = r.value<double>();
  s.dt_last = r.value<double>();
  const double dt_next = r.value<double>();
  s.dt_control_prev = r.value<double>();
  s.cycle = static_cast<long>(r.value<std::int64_t>());
  const auto dt_zone = static_cast<Index>(r.value<std::int64_t>());
  s.have_previous_forces = r.value<std::uint8_t>() != 0;
  s.energy_initial = r.value<double>();
  s.boundary_work = r.value<double>();
  s.source_work = r.value<double>();
  const char* names[] = {"x", "y", "vx", "vy", "e", "q", "fx", "fy", "sxx", "syy", "sxy", "plastic", "burn"};
  int i = 0;
  for (auto* v : {&s.x, &s.y, &s.vx, &s.vy, &s.e, &s.q, &s.corner_fx, &s.corner_fy, &s.sxx, &s.syy, &s.sxy, &s.plastic,
                  &s.burn})
    r.array(*v, names[i++]);
  s.recompute_state();
  s.dt_next = dt_next;
  s.dt_zone = dt_zone;
}

}  // namespace stagger
