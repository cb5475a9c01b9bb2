#include "mesh/projected_area.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clothsim::mesh
{
  double
  projected_area(const std::vector<std::array<Point<2>, 3>> &triangles,
                 const unsigned int                          resolution)
  {
    if (triangles.empty())
      return 0.;
    Point<2> low(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    Point<2> high = -low;
    for (const auto &triangle : triangles)
      for (const Point<2> &p : triangle)
        for (unsigned int d = 0; d < 2; ++d)
          {
            low[d]  = std::min(low[d], p[d]);
            high[d] = std::max(high[d], p[d]);
          }
    const double      width  = std::max(high[0] - low[0], 1e-300);
    const double      height = std::max(high[1] - low[1], 1e-300);
    const double      dx = width / resolution, dy = height / resolution;
    std::vector<char> covered(static_cast<std::size_t>(resolution) * resolution, 0);

    // Cell (i, j) has its centre at low + ((i + 1/2) dx, (j + 1/2) dy); a centre is in
    // the triangle if the three edge functions have one sign (either orientation).
    const auto cell = [&](const double x, const double h) {
      return static_cast<int>(std::floor(x / h - 0.5));
    };
    for (const auto &t : triangles)
      {
        const double x0 = std::min({t[0][0], t[1][0], t[2][0]}) - low[0];
        const double x1 = std::max({t[0][0], t[1][0], t[2][0]}) - low[0];
        const double y0 = std::min({t[0][1], t[1][1], t[2][1]}) - low[1];
        const double y1 = std::max({t[0][1], t[1][1], t[2][1]}) - low[1];
        const int    i0 = std::max(0, cell(x0, dx) + 1),
                  i1    = std::min<int>(resolution - 1, cell(x1, dx));
        const int j0    = std::max(0, cell(y0, dy) + 1),
                  j1    = std::min<int>(resolution - 1, cell(y1, dy));
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
            {
              const double x = low[0] + (i + 0.5) * dx, y = low[1] + (j + 0.5) * dy;
              double       edge[3];
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const Point<2> &a = t[k], &b = t[(k + 1) % 3];
                  edge[k] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
                }
              const bool inside = (edge[0] >= 0. && edge[1] >= 0. && edge[2] >= 0.) ||
                                  (edge[0] <= 0. && edge[1] <= 0. && edge[2] <= 0.);
              if (inside)
                covered[static_cast<std::size_t>(j) * resolution + i] = 1;
            }
      }
    return std::count(covered.begin(), covered.end(), 1) * dx * dy;
  }
} // namespace clothsim::mesh
