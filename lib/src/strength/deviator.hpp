#pragma once
// The in-plane deviatoric stress of a zone; the out-of-plane part is S_zz = -(S_xx + S_yy)
// (docs/algorithm.md §7).

namespace stagger {

struct Deviator {
  double xx = 0, yy = 0, xy = 0;
};

}  // namespace stagger
