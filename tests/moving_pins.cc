// Pinned vertices moving along a prescribed path (tests/scenes/moving_pins.prm): at every
// step the pinned probe sits exactly on the path u = (0.05 sin 2πt, 0, 0.05 (1 - cos
// 2πt)) m (1e-12 m), and the free bottom corner is dragged along: it moves more than 1 cm
// in +x on the way (the pins reach 5 cm at t = 0.25 s) and more than 5 cm up by t = 0.5 s
// (pins: 10 cm).

#include "test_support.h"

#include <cmath>

using namespace clothsim::test;

int
main(int argc, char **argv)
{
  Environment       env(argc, argv);
  const std::string output = scratch_directory("clothsim-moving-pins");
  if (run_clothsim(
        {source_path("tests/scenes/moving_pins.prm"), "--output-dir", output}) != 0)
    return 1;

  const auto probes        = read_csv(output + "/probes.csv");
  double     worst_pin     = 0.;
  double     bottom_ux_max = 0., bottom_uz = 0.;
  for (unsigned int r = 0; r < probes.rows.size(); ++r)
    {
      const double t = probes.number(r, "time");
      if (probes.rows[r][probes.column("probe")] == "pin")
        worst_pin = std::max(
          {worst_pin,
           std::abs(probes.number(r, "ux") - 0.05 * std::sin(2 * M_PI * t)),
           std::abs(probes.number(r, "uy")),
           std::abs(probes.number(r, "uz") - 0.05 * (1 - std::cos(2 * M_PI * t)))});
      else
        {
          bottom_ux_max = std::max(bottom_ux_max, probes.number(r, "ux"));
          bottom_uz     = probes.number(r, "uz");
        }
    }
  env.pcout << "largest distance of the pin from its path " << worst_pin
            << " m; bottom corner: largest ux " << bottom_ux_max << " m, uz at t = 0.5 s "
            << bottom_uz << " m" << std::endl;
  const bool passed = worst_pin < 1e-12 && bottom_ux_max > 0.01 && bottom_uz > 0.05;
  return finish(env.pcout, passed);
}
