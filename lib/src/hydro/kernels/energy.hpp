#pragma once
// The compatible internal-energy update (docs/algorithm.md §1, steps 3 and 7): the work of a
// zone's corner forces on its points' velocities, the same forces that moved the points.
namespace stagger {

// sum_c f_c . u_c over the n corners of a zone (corner order: the same sum every time).
[[gnu::always_inline]] inline double corner_work(int n, const double* fx, const double* fy, const double* ux,
                                                 const double* uy) {
  double work = 0;
  for (int k = 0; k < n; ++k) work += fx[k] * ux[k] + fy[k] * uy[k];
  return work;
}

// e after a time h of the work rate `work` on a zone of mass M: e - h work / M. The
// predictor (step 3) takes h = dt/2 with f^{n-1/2} . v^n; the corrector (step 7) h = dt with
// f^{n+1/2} . v_bar.
[[gnu::always_inline]] inline double energy_after_work(double e, double h, double work, double mass) {
  return e - h * work / mass;
}

}  // namespace stagger
