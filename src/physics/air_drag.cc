#include "physics/air_drag.h"

#include <cmath>

namespace clothsim::physics
{
  double
  air_dissipation(const AirProperties &air,
                  const double         area,
                  const Tensor<1, 3>  &normal,
                  const Tensor<1, 3>  &relative_velocity,
                  Tensor<1, 3>        *first,
                  Tensor<2, 3>        *second)
  {
    const double       scale   = air.density * area;
    const double       v_n     = relative_velocity * normal;
    const Tensor<1, 3> v_t     = relative_velocity - v_n * normal;
    const double       speed_n = std::abs(v_n);
    const double       speed_t = v_t.norm();
    const double       c_n     = air.normal_drag;
    const double       c_t     = air.tangential_drag;
    const double       dissipated =
      scale * (c_n * speed_n * speed_n * speed_n + c_t * speed_t * speed_t * speed_t) /
      6.;
    if (first != nullptr)
      *first = 0.5 * scale * (c_n * speed_n * v_n * normal + c_t * speed_t * v_t);
    if (second != nullptr)
      {
        // C_n |v_n| n⊗n + ½ C_t (|v_t| P + v_t⊗v_t/|v_t|), P = I - n⊗n.
        const Tensor<2, 3> nn = outer_product(normal, normal);
        *second               = (c_n * speed_n) * nn;
        if (speed_t > 0.)
          *second += (0.5 * c_t) * (speed_t * (unit_symmetric_tensor<3>() - nn) +
                                    outer_product(v_t, v_t) / speed_t);
        *second *= scale;
      }
    return dissipated;
  }


  AirDrag::AirDrag(const AirProperties &air, const WindField &wind)
    : ElementTerm("air", TermKind::dissipative)
    , air(air)
    , wind(wind)
  {}


  void
  AirDrag::add_to_step(const ElementState &element,
                       const StepTerms    &step,
                       double             &value,
                       LocalVector        *gradient,
                       LocalMatrix        *hessian) const
  {
    const double w_d = step.damping_weight;
    if (w_d == 0.)
      return;

    // Geometry lagged at the damping centre y = X + u_n.
    TrianglePositions y;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 3; ++c)
        y[a][c] = element.reference[a][c] + element.previous[3 * a + c];
    const Tensor<1, 3> twice_area_normal = cross_product_3d(y[1] - y[0], y[2] - y[0]);
    const double       twice_area        = twice_area_normal.norm();
    if (!(twice_area > 0.))
      return; // a collapsed triangle meets no air
    const Tensor<1, 3> normal = twice_area_normal / twice_area;

    // v_r = w_d (mean u - mean u_n) - w(x_c, t).
    Tensor<1, 3> velocity;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 3; ++c)
        velocity[c] += (w_d / 3.) * (element.u[3 * a + c] - element.previous[3 * a + c]);
    if (wind)
      {
        const Point<3> centroid((y[0][0] + y[1][0] + y[2][0]) / 3.,
                                (y[0][1] + y[1][1] + y[2][1]) / 3.,
                                (y[0][2] + y[1][2] + y[2][2]) / 3.);
        velocity -= wind(centroid, step.time);
      }

    Tensor<1, 3> first;
    Tensor<2, 3> second;
    value += air_dissipation(air,
                             0.5 * twice_area,
                             normal,
                             velocity,
                             &first,
                             hessian != nullptr ? &second : nullptr) /
             w_d;
    if (gradient != nullptr)
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = 0; c < 3; ++c)
          (*gradient)[3 * a + c] += first[c] / 3.;
    if (hessian != nullptr)
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          for (unsigned int c = 0; c < 3; ++c)
            for (unsigned int d = 0; d < 3; ++d)
              (*hessian)[3 * a + c][3 * b + d] += (w_d / 9.) * second[c][d];
  }
} // namespace clothsim::physics
