#pragma once
// The conservative remap of the ALE phase (docs/ale.md, "Remap"): swept-face fluxes between
// an old and a new position of the same mesh, piecewise-linear reconstruction from
// least-squares gradients with a Barth-Jespersen limiter, zone quantities per unit mass, and
// the momentum and kinetic energy of the points through the corners (subcells) so that the
// corner masses stay consistent with the zone and point masses (Loubere & Shashkov 2005).
#include <span>
#include <vector>

#include "stagger/mesh.hpp"

namespace stagger {

// The state a remap carries, as raw arrays of the mesh's sizes. Inputs on the old mesh are
// replaced by the values on the new mesh.
struct RemapFields {
  double* zone_mass = nullptr;    // nzones
  double* corner_mass = nullptr;  // ncorners: median-mesh corner masses, summing to the zone masses
  double* point_mass = nullptr;   // npoints: the Lagrangian point masses (sums of corner masses)
  double* vx = nullptr;           // npoints
  double* vy = nullptr;
  // Zone quantities per unit mass (specific internal energy, deviatoric stress, ...): each is
  // remapped as the density of mass * value. A zone whose value is not finite (the lighting
  // time of inert zones) keeps it and exchanges none of it.
  std::vector<double*> specific;
  // Output, npoints: the kinetic energy of each point's dual cell carried by the remap (the
  // old 1/2 M v^2 plus the fluxes); minus 1/2 M' v'^2 it is what the kinetic-energy fix-up
  // gives to the internal energy.
  double* point_kinetic = nullptr;
};

// Swept-region remapper for one mesh topology: allocates its workspace once.
class Remapper {
 public:
  // zone_material[z]: zones of different materials exchange nothing (their shared points
  // must not move, so their faces sweep no area). rz (docs/ale.md, "ALE in rz"): volumes,
  // moments and fluxes are per radian (int r dA, x = r); the points on x = 0 are massless and
  // exchange nothing with their neighbours' dual cells: their velocity is the reconstruction
  // at their new position.
  Remapper(const Mesh& mesh, std::span<const int> zone_material, bool rz = false);

  // Remaps `fields` from the positions (xo, yo) to (xn, yn). limiter: Barth-Jespersen on every
  // gradient. Throws stagger::Error naming the zone or point if a mass would become
  // non-positive (a displacement too large for a swept-face remap: see remap_substeps).
  void remap(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& fields, bool limiter);

  // Number of equal sub-steps that keeps every point's displacement below `fraction` of its
  // shortest edge (on either mesh); 1 for small displacements.
  int substeps(const double* xo, const double* yo, const double* xn, const double* yn, double fraction) const;

  const Mesh& mesh() const { return mesh_; }
  // Zones whose corner masses were reset so far (see remap()).
  long repaired_zones() const { return repaired_; }
  // The donor remainder bound of the limited remap (docs/ale.md, "Reconstruction and limiter"),
  // on by default; off only for the tests that show what it prevents.
  void set_remainder_bound(bool on) { remainder_bound_ = on; }
  // Zone remaps so far in which the donor remainder bound changed outflows (see remap()).
  long bounded_zones() const { return bounded_; }

 private:
  struct ZoneSide;  // one side of a zone in the flux sweep (remap.cpp)

  // Set-up (the constructor's stages).
  void find_sides(std::span<const int> zone_material);
  void find_neighbours(std::span<const int> zone_material);
  void allocate_workspace();
  void order_flux_sums();

  // The remap's stages, in the order remap_impl runs them: the reconstruction
  // (remap_reconstruction.cpp), the face fluxes (remap_fluxes.cpp), the new values (remap_update.cpp).
  template <bool Rz>
  void remap_impl(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f, bool limiter);
  template <bool Rz>
  void mark_active(const double* xo, const double* yo, const double* xn, const double* yn);
  template <bool Rz>
  void old_geometry(const double* xo, const double* yo, const RemapFields& f);
  template <bool Rz>
  void old_corners(Index z, const double* xo, const double* yo, const RemapFields& f);
  void least_squares_matrices(const double* xo, const double* yo);
  void reconstruction_gradients(const RemapFields& f, bool limiter);
  void zone_gradients(const double* q, bool limiter, double* gx, double* gy, double* lo, double* hi);
  void point_gradients(const double* qa, const double* qb, bool limiter, double* gax, double* gay, double* gbx,
                       double* gby);
  void corner_gradients(const double* xo, const double* yo);
  template <bool Rz>
  void face_fluxes(const double* xo, const double* yo, const double* xn, const double* yn, const RemapFields& f,
                   bool limiter, bool direct, bool bound);
  void clear_zone_slots(Index z, std::size_t nf, bool direct);
  template <bool Rz>
  void half_side_fluxes(const ZoneSide& side, const double* xo, const double* yo, const double* xn, const double* yn,
                        const RemapFields& f, bool limiter, bool direct, bool bound);
  template <bool Rz>
  void centre_segment_flux(const ZoneSide& side, double gnx, double gny, const double* xo, const double* yo,
                           const RemapFields& f, bool direct);
  double remainder_keep(const RemapFields& f, Index z, std::size_t i, double m0, double m1) const;
  void keep_outflows(const RemapFields& f, Index z, std::size_t i, double t);
  void direct_remainder_bound(const RemapFields& f);
  void direct_zone_corner_values(RemapFields& f);
  void gather_fluxes(RemapFields& f, bool limiter);
  void slot_remainder_bound(const RemapFields& f);
  void gather_zone_values(RemapFields& f);
  void gather_corner_point_sums(RemapFields& f);
  template <bool Rz>
  void repair_corner_masses(const double* xn, const double* yn, RemapFields& f);
  template <bool Rz>
  void point_momentum(const double* xo, const double* yo, const double* xn, const double* yn, RemapFields& f);

  const Mesh& mesh_;
  bool rz_ = false;
  std::vector<char> axis_point_;     // rz: per point, on x = 0
  std::vector<char> segment_point_;  // per corner: its centre segment moves momentum between points
  std::vector<Index> side_zone_;     // per corner: the zone across the corner's side, -1 if none
  std::vector<Index> side_corner0_;  // per corner: that zone's corner at this corner's point
  std::vector<Index> side_corner1_;  // ... and at the side's other point
  std::vector<char> boundary_point_;
  std::vector<char> limit_vertex_;  // per corner: the limiter bounds the zone's reconstruction at its point
  std::vector<Index> zone_nbr_begin_, zone_nbr_;    // zones sharing a point with z (not z)
  std::vector<Index> point_nbr_begin_, point_nbr_;  // points sharing an edge with p
  // Workspace.
  std::vector<double> area_, cx_, cy_, rho_, grx_, gry_, rlo_, rhi_;
  std::vector<double> zlsq_, plsq_;  // per zone / point: the 2x2 pseudo-inverse (xx, xy, yy)
  std::vector<double> qgx_, qgy_, qmin_, qmax_, vgx_, vgy_, wgx_, wgy_;
  std::vector<double> crho_, ccx_, ccy_, cgx_, cgy_;  // per corner: density, centroid, gradient
  std::vector<double> gox_, goy_;  // per zone: the mean of the old vertices (the corners' centre point)
  // Per corner, from the zone's centroid on the old mesh: its point, and the midpoint of its
  // side (zero where the side is not shared, which the limiter skips); per zone-neighbour
  // entry, the neighbour's centroid. Computed once per remap for every gradient.
  std::vector<double> lvx_, lvy_, lmx_, lmy_, ncx_, ncy_;
  std::vector<double> pdx_, pdy_;  // per point-neighbour entry: the edge to the neighbour, old mesh
  std::vector<double> dm_point_, dpx_, dpy_, dke_;
  std::vector<char> point_touched_;
  // The fluxes are computed face by face (in parallel) into slots, then summed per zone,
  // corner and point in the order a serial sweep over the zones would add them, so the
  // result is bitwise the same on any number of threads. Slots: 2c + h for half h of the
  // side of corner c (from the zone that owns it, the lower-numbered), 2 nc + c for the
  // centre segment of corner c. Lists: slot * 2 + 1 where the flux is subtracted.
  std::vector<double> flux_mass_, flux_q_, seg_px_, seg_py_, seg_ke_;
  std::vector<char> flux_active_;
  std::vector<double> keep_;  // per field and zone: fraction of its outflows' deviation kept (remainder bound)
  std::vector<Index> zone_list_begin_, zone_list_, corner_list_begin_, corner_list_, point_list_begin_, point_list_;
  // On one thread the fluxes go straight into these sums (and dm_point_, ...) instead.
  std::vector<double> zone_dm_, corner_dm_, zone_dq_;
  std::vector<char> zone_hit_;
  std::vector<Index> bound_zones_;  // one thread: the zones where the donor remainder bound acts
  std::vector<char> zone_resum_;    // ... and the zones whose sums it changes
  // Per remap: points that move, zones with a moving point (the only ones with fluxes), the
  // points of those zones and the zones with such a point (remap_impl).
  std::vector<char> point_moved_, zone_active_, point_near_, zone_near_;
  long repaired_ = 0;
  bool remainder_bound_ = true;
  long bounded_ = 0;
};

}  // namespace stagger
