#pragma once

// Pressure on the current surface, as a potential (so that Newton's energy line search
// and symmetric solvers still apply):
//   Φ_p(x) = -p V(x),   V = Σ_T (1/6) (x0 - c) · ((x1 - c) × (x2 - c))
// the volume of the cones from a fixed point c to the triangles. Its force on a vertex is
// p Σ_T N_T / 6 (N_T = (x1 - x0) × (x2 - x0), so |N_T|/2 is the area) plus, on a free
// boundary vertex only, p (x_a - x_b) × (x - c) / 6 from the two boundary neighbours a,
// b: the follower load p n dA wherever the loaded surface is closed or its boundary is
// held (pressurised membranes, plates, vessels), independent of c there. p > 0 pushes
// along the mesh normal N. Per triangle:
//   ∂V/∂x0 = (x1 × x2)/6,  ∂V/∂x1 = (x2 × x0)/6,  ∂V/∂x2 = (x0 × x1)/6  (x relative to c)
//   ∂²V/∂x_i,a ∂x_j,b = ± ε_abk x_m,k / 6, + for (i, j, m) a cyclic permutation of
//   (0, 1, 2), - otherwise (and 0 for i = j).

#include <deal.II/base/point.h>

#include "physics/membrane.h"

namespace clothsim::physics
{
  using namespace dealii;

  // Φ_p of one triangle (J), its gradient (N) and, if non-null, Hessian (N/m), for the
  // pressure p (Pa) and the cones' apex c (m).
  double
  pressure_potential_gradient_hessian(const double             pressure,
                                      const TrianglePositions &x,
                                      const Point<3>          &apex,
                                      ElementVector           &gradient,
                                      ElementMatrix           *hessian);
} // namespace clothsim::physics
