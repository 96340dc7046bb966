#pragma once
// The rezone phase of ALE (docs/ale.md, "Rezone"): new point positions from the Lagrangian
// ones, a pure function of explicit inputs. The remap (docs/ale.md, "Remap") then moves the
// fields from the Lagrangian mesh to the rezoned one; the rezone knows nothing of fields.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "stagger/mesh.hpp"
#include "stagger/problem.hpp"

namespace stagger {

// How the smooth target positions are found (docs/ale.md, "Rezone").
enum class RezoneMethod {
  // Winslow (equipotential) smoothing: Gauss-Seidel sweeps of the Winslow equations
  // alpha x_xixi - 2 beta x_xieta + gamma x_etaeta = 0, the derivatives fitted by least
  // squares over each point's one-ring laid out in a local logical space (Knupp 1999). A
  // uniform Cartesian mesh is a fixed point. The fast default.
  winslow,
  // Point-by-point minimisation of the corner functional sum |T|^2 / det T, T the corner
  // Jacobian relative to the reference (initial) mesh's corner (Brackbill-Saltzman smoothness
  // in target-matrix form): the initial mesh is a fixed point, so graded and unstructured
  // meshes keep their own shape; every step keeps the zones around the point valid. Costs
  // several times more per sweep than winslow.
  reference_jacobian,
};

// The local logical layout of Winslow's stencils (docs/ale.md, "Winslow smoothing").
enum class WinslowLayout {
  // Knupp (1999): each point's fan laid out as regular polygons in equal sectors. The
  // smoothed mesh tends to Winslow's map of that layout: a graded, skewed or unstructured mesh
  // is pulled toward regular shapes.
  regular,
  // The reference (initial) mesh is the logical space: each neighbour's offset is its initial
  // offset from the point, in units of the point's mean initial edge length. The initial mesh
  // is a fixed point (any grading, any gmsh mesh), and a distorted mesh is pulled back toward
  // it. The same as `regular` on a uniform Cartesian mesh.
  reference,
};

// What the rezone may do with a point.
enum class RezonePointKind : std::uint8_t {
  interior,  // moves freely
  slide,     // on the domain boundary, on one tag: moves along its boundary edges
  fixed,     // stays Lagrangian: material interface, tag junction, periodic tag, or a
             // boundary point with other than two boundary edges
};

// Built once from the mesh topology and the boundary conditions (make_rezone_constraints).
struct RezoneConstraints {
  std::vector<RezonePointKind> kind;  // per point
  // Slide points: their two neighbours along the boundary (point ids), else -1.
  std::vector<std::array<Index, 2>> boundary_neighbours;
  Index num_interior = 0, num_slide = 0, num_fixed = 0;
  // Winslow stencils: the one-ring of point p (its zones' other vertices, counter-clockwise)
  // is stencil_points[stencil_begin[p] .. stencil_begin[p + 1]); stencil_id[p] indexes the
  // least-squares derivative weights of its local logical layout (-1: no stencil, the point
  // does not move under Winslow). Points with the same zone sizes around them share weights.
  std::vector<Index> stencil_begin{0}, stencil_points, stencil_id;
  // Per stencil: offset into stencil_weights; per neighbour 3 weights (x_xixi, x_xieta,
  // x_etaeta of the logical second derivatives) and 2 (x_xi, x_eta), then the 5 row sums.
  std::vector<Index> weights_begin{0};
  std::vector<double> stencil_weights;
  // The points that may move, by colour: no two points of a colour share a zone, so a sweep
  // updates each colour's points independently (in parallel, same result on any thread count).
  std::vector<Index> colour_begin{0}, colour_points;
};

// Rezone options. The defaults are those of the [ale] scene section (docs/scenes.md).
struct RezoneOptions {
  RezoneMethod method = RezoneMethod::winslow;
  // x_new = x_lag + relaxation (x_smooth - x_lag); 0 returns the Lagrangian mesh bitwise,
  // 1 the smoothed mesh. In [0, 1].
  double relaxation = 0.5;
  // Gauss-Seidel sweeps of the point-by-point minimisation (each sweep visits every free
  // point once, one safeguarded Newton step). >= 0; 0 also returns the Lagrangian mesh.
  int iterations = 1;
  // A boundary point slides only where its two boundary edges turn by at most this angle
  // (at the Lagrangian positions); elsewhere it is a corner and stays. Degrees, in [0, 90).
  double corner_angle_degrees = 0.5;
  // No point moves further than this fraction of its shortest Lagrangian edge (keeps the
  // swept regions of a face-flux remap within the neighbouring zones). In (0, 1].
  double max_move = 0.5;
  // reference_jacobian only: weight w of a size term w (D / tau + tau / D) per corner, D the
  // corner's area relative to its reference corner (det T) and tau the mean D of the corners
  // around the point, so that a zone much smaller (relative to its initial area) than its
  // neighbours grows back toward their size (docs/ale.md, "Reference-Jacobian smoothing").
  // 0: shapes only (scale-invariant). >= 0.
  double size_weight = 0;
};

// What the rezone did (for history / diagnostics).
struct RezoneResult {
  double max_displacement = 0;  // largest |x_new - x_lag| over points
  Index backed_off_points = 0;  // points whose relaxation the validity guard reduced
  int backoff_rounds = 0;       // guard rounds needed (0: the first result was valid)
};

// Scratch arrays reused between calls (sized on first use), so that the rezone allocates
// nothing in the time loop after the first call.
struct RezoneWorkspace {
  std::vector<double> target;      // per corner: the functional's target constants (4 each)
  std::vector<double> xs, ys;      // per point: the smoothed positions before relaxation
  std::vector<double> arc;         // per point: slide points' arc length along the boundary
  std::vector<double> move_limit;  // per point: max_move * shortest Lagrangian edge
  std::vector<double> weight;      // per point: relaxation actually applied
  std::vector<std::uint8_t> flag;  // per zone: folded by the rezone (validity guard)
};

// Classifies every point. `boundaries` are the problem's conditions (periodic tags are
// fixed, so that partner points stay matched); `zone_material` (size nzones, or empty to use
// mesh.zone_region) marks interfaces: a point whose zones have more than one value is fixed,
// so pure zones stay pure. A point on two or more tags is fixed (the boundary condition
// changes there). `layout` chooses Winslow's logical layout (the reference one reads the
// mesh's initial positions mesh.x, mesh.y). Throws stagger::Error naming the zone if
// zone_material has the wrong size.
RezoneConstraints make_rezone_constraints(const Mesh& mesh, std::span<const BoundaryCondition> boundaries,
                                          std::span<const Index> zone_material = {},
                                          WinslowLayout layout = WinslowLayout::regular);

// The rezone: from the Lagrangian positions (x_lag, y_lag) to (x_new, y_new), all of size
// npoints. (x_ref, y_ref) is the reference mesh (the initial one), read only by
// reference_jacobian. Guarantee: every zone that is valid at the Lagrangian positions
// (positive area, no crossing edges: hydro/kernels/zone_validity.hpp) is valid in the result,
// and one whose median-mesh corners all have positive area keeps them positive;
// points whose move would break one get their relaxation halved, down to the Lagrangian
// position. Fixed points are copied bitwise; slide points stay on their old boundary edges.
// Throws stagger::Error for options out of range. x_new/y_new must not alias x_lag/y_lag.
RezoneResult rezone(const Mesh& mesh, const RezoneConstraints& constraints, const RezoneOptions& options,
                    std::span<const double> x_lag, std::span<const double> y_lag, std::span<const double> x_ref,
                    std::span<const double> y_ref, std::span<double> x_new, std::span<double> y_new,
                    RezoneWorkspace& workspace);

// The last stage of rezone on its own (for tests and for other smoothers):
// (x_new, y_new) = x_lag + relaxation (x_smooth - x_lag), fixed points bitwise Lagrangian; then
// every zone valid at the Lagrangian positions and not at the new ones halves the relaxation
// of its points, round after round, and after eight rounds puts them back to their Lagrangian
// positions (the same for a zone whose median-mesh corners lose their positive area). Every
// zone valid at (x_lag, y_lag) is valid at (x_new, y_new).
RezoneResult relax_and_guard(const Mesh& mesh, const RezoneConstraints& constraints, double relaxation,
                             std::span<const double> x_lag, std::span<const double> y_lag,
                             std::span<const double> x_smooth, std::span<const double> y_smooth,
                             std::span<double> x_new, std::span<double> y_new, RezoneWorkspace& workspace);

// Zone quality, for a remap trigger and for reports.
enum class QualityMeasure {
  // min over corners of sin(corner angle) = (u x v) / (|u| |v|): 1 for rectangles, <= 0 for
  // a non-convex or inverted zone.
  scaled_jacobian,
  // min over corners of 2 det T / |T|^2 with T the corner Jacobian relative to the reference
  // mesh's corner (the inverse of the shape distortion): 1 where the zone has its reference
  // shape (any size), -> 0 as it degenerates, <= 0 inverted. Needs (x_ref, y_ref).
  reference_shape,
};

struct QualitySummary {
  double worst = 1;       // smallest zone quality
  Index worst_zone = -1;  // where
  double mean = 1;        // mean over zones
};

// Quality of zone z at (x, y) (x_ref/y_ref read only by reference_shape).
double zone_quality(const Mesh& mesh, Index z, QualityMeasure measure, std::span<const double> x,
                    std::span<const double> y, std::span<const double> x_ref, std::span<const double> y_ref);

// Worst and mean zone quality over the mesh.
QualitySummary mesh_quality_summary(const Mesh& mesh, QualityMeasure measure, std::span<const double> x,
                                    std::span<const double> y, std::span<const double> x_ref,
                                    std::span<const double> y_ref);

}  // namespace stagger
