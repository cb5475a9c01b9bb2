// Bending element (midedge-director shell, physics/bending.h): a flat right isosceles
// triangle bent isometrically onto a cylinder of radius R has W / (D/2 κ² |T̄|) -> 1 and
// curvature_change_norm / κ -> 1 as the triangle shrinks (s = R/10, R/100, R/1000, two
// orientations), with the error falling at least twofold per tenfold refinement. Every
// check asserts a bound and prints the worst value it measured.

#include "physics/bending.h"
#include "test_checks.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace clothsim::physics;
using namespace clothsim::test;

int
main()
{
  ConditionalOStream out(std::cout);
  // Isometric bending onto a cylinder of radius R about the line x = 0, z = R:
  //      φ(u, v) = (R sin(u/R), v, R (1 - cos(u/R))),
  //      n(u, v) = (-sin(u/R), 0, cos(u/R)),
  //    curvature κ = 1/R across the axis, 0 along it, so W = |T̄| D/2 κ² for any ν.
  //    Reference: the flat right isosceles triangle P0, P0 + s (cos α, sin α),
  //    P0 + s (-sin α, cos α) in z = 0 (normal +z, the rest directors); current: its
  //    image under φ with r_i = n at the preimage of edge i's midpoint, ψ = 0. The
  //    tilts' sign does not matter: W is quadratic in II - ĪI, and ĪI = 0 here.
  WorstCase cylinder_limit_check{"cylinder, |W / (D/2 κ² |T̄|) - 1| at s = R/1000", 1e-2};
  WorstCase cylinder_norm_check{"cylinder, |curvature_change_norm / κ - 1| at s = R/1000",
                                1e-2};
  WorstCase cylinder_rate_check{
    "cylinder, |ratio(s/10) - 1| / |ratio(s) - 1|, s = R/10 -> R/100 -> R/1000", 0.5};
  {
    const double          R = 0.7, kappa = 1. / R;
    const BendingMaterial material{2.5, 0.3, DirectorFunction::angle};
    for (const double alpha : {0., 0.5})
      {
        std::ostringstream where;
        where << "  cylinder R " << R << ", orientation " << alpha << " rad\n";
        double previous_error = 0.;
        for (const double s : {R / 10., R / 100., R / 1000.})
          {
            const double u0 = 0.2 * R, v0 = 0.1 * R;
            const double u[3] = {u0, u0 + s * std::cos(alpha), u0 - s * std::sin(alpha)};
            const double v[3] = {v0, v0 + s * std::sin(alpha), v0 + s * std::cos(alpha)};
            TrianglePositions reference, x;
            for (unsigned int k = 0; k < 3; ++k)
              {
                reference[k] = Point<3>(u[k], v[k], 0.);
                x[k] =
                  Point<3>(R * std::sin(u[k] / R), v[k], R * (1. - std::cos(u[k] / R)));
              }
            EdgeDirectors rest_directors, directors;
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double u_mid          = 0.5 * (u[(i + 1) % 3] + u[(i + 2) % 3]);
                rest_directors.reference[i] = Tensor<1, 3>({0., 0., 1.});
                directors.reference[i] =
                  Tensor<1, 3>({-std::sin(u_mid / R), 0., std::cos(u_mid / R)});
                rest_directors.sign[i] = directors.sign[i] = (i == 1 ? -1. : 1.);
              }
            const EdgeAngles      psi = {{0., 0., 0.}};
            const BendingRestData rest =
              bending_rest_data(material, reference, rest_directors);
            const double area  = 0.5 * s * s;
            const double ratio = bending_energy(material, rest, x, directors, psi) /
                                 (0.5 * material.rigidity * kappa * kappa * area);
            const double norm_ratio =
              curvature_change_norm(material, rest, x, directors, psi) / kappa;
            const double error = std::abs(ratio - 1.);
            out << "cylinder, orientation " << alpha << " rad, s = R/" << R / s
                << ": W / (D/2 κ² |T̄|) = " << std::setprecision(10) << ratio
                << ", curvature change norm / κ = " << norm_ratio << std::setprecision(6)
                << '\n';
            if (s < R / 500.)
              {
                cylinder_limit_check.record(out, error, where.str());
                cylinder_norm_check.record(out, std::abs(norm_ratio - 1.), where.str());
              }
            if (previous_error > 0.)
              cylinder_rate_check.record(out, error / previous_error, where.str());
            previous_error = error;
          }
      }
  }


  bool passed = true;
  for (const WorstCase *check :
       {&cylinder_limit_check, &cylinder_norm_check, &cylinder_rate_check})
    passed &= check->report(out);
  return finish(out, passed);
}
