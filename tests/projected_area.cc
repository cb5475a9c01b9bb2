// mesh/projected_area: the area of the union of triangles' shadows against exact areas.
// 1. The unit square as two triangles: 1 (its outline on the sampling grid's border).
// 2. Two unit squares overlapping by half, four triangles: 1.5 (the overlap counted
// once).
// 3. A regular 400-gon of radius 0.15 m (the Cusick specimen) as a fan of triangles, and
//    the fan with every other triangle moved onto another one (half the slots covered
//    twice, half not at all): the polygon's area within 1e-4 relative, and half of it
//    within 2e-3 (its outline, 400 radial edges, is 60 times longer).

#include "mesh/projected_area.h"

#include "test_checks.h"

using namespace clothsim;
using namespace clothsim::test;
using Triangle = std::array<Point<2>, 3>;

int
main(int argc, char **argv)
{
  Environment                 env(argc, argv);
  ConditionalOStream         &pcout  = env.pcout;
  const std::vector<Triangle> square = {
    Triangle{{Point<2>(0, 0), Point<2>(1, 0), Point<2>(1, 1)}},
    Triangle{{Point<2>(0, 0), Point<2>(1, 1), Point<2>(0, 1)}}};
  bool passed = check_near(pcout, "unit square", mesh::projected_area(square), 1., 1e-12);

  std::vector<Triangle> two = square;
  for (const Triangle &t : square)
    two.push_back(Triangle{{Point<2>(t[0][0] + 0.5, t[0][1]),
                            Point<2>(t[1][0] + 0.5, t[1][1]),
                            Point<2>(t[2][0] + 0.5, t[2][1])}});
  passed &= check_near(
    pcout, "two squares overlapping by half", mesh::projected_area(two), 1.5, 1e-12);

  const unsigned int    n = 400;
  const double          r = 0.15, pi = numbers::PI;
  std::vector<Triangle> fan, folded;
  for (unsigned int k = 0; k < n; ++k)
    {
      const Point<2> a(r * std::cos(2. * pi * k / n), r * std::sin(2. * pi * k / n));
      const Point<2> b(r * std::cos(2. * pi * (k + 1) / n),
                       r * std::sin(2. * pi * (k + 1) / n));
      fan.push_back(Triangle{{Point<2>(), a, b}});
      // n/2 + k has the parity of k (n/2 even): the odd slots go onto the even ones.
      const Point<2> c(r * std::cos(2. * pi * (k + n / 2 + 1) / n),
                       r * std::sin(2. * pi * (k + n / 2 + 1) / n));
      const Point<2> d(r * std::cos(2. * pi * (k + n / 2 + 2) / n),
                       r * std::sin(2. * pi * (k + n / 2 + 2) / n));
      folded.push_back(k % 2 == 0 ? Triangle{{Point<2>(), a, b}}
                                  : Triangle{{Point<2>(), c, d}});
    }
  const double polygon = 0.5 * n * r * r * std::sin(2. * pi / n);
  passed &= check_near(
    pcout, "400-gon / its area", mesh::projected_area(fan) / polygon, 1., 1e-4);
  passed &= check_near(pcout,
                       "half the fan moved onto the other half / its area",
                       mesh::projected_area(folded) / polygon,
                       0.5,
                       2e-3);
  return finish(pcout, passed);
}
