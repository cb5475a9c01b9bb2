#include "physics/pressure.h"

namespace clothsim::physics
{
  double
  pressure_potential_gradient_hessian(const double             pressure,
                                      const TrianglePositions &x,
                                      const Point<3>          &apex,
                                      ElementVector           &gradient,
                                      ElementMatrix           *hessian)
  {
    std::array<Tensor<1, 3>, 3> y;
    for (unsigned int v = 0; v < 3; ++v)
      y[v] = x[v] - apex;
    const double scale = -pressure / 6.;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const Tensor<1, 3> dV = cross_product_3d(y[(i + 1) % 3], y[(i + 2) % 3]);
        for (unsigned int a = 0; a < 3; ++a)
          gradient[3 * i + a] = scale * dV[a];
      }
    if (hessian != nullptr)
      {
        ElementMatrix &H = *hessian;
        for (auto &row : H)
          row.fill(0.);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              if (i == j)
                continue;
              const unsigned int m    = 3 - i - j;
              const double       sign = (j == (i + 1) % 3) ? 1. : -1.;
              // ε_abk y_m,k: the cross-product matrix of y_m with a minus sign.
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int b = 0; b < 3; ++b)
                  {
                    const unsigned int k = 3 - a - b;
                    if (a == b)
                      continue;
                    const double epsilon    = (b == (a + 1) % 3) ? 1. : -1.;
                    H[3 * i + a][3 * j + b] = scale * sign * epsilon * y[m][k];
                  }
            }
      }
    return scale * (y[0] * cross_product_3d(y[1], y[2]));
  }
} // namespace clothsim::physics
