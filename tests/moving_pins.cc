// Pinned vertices moving along a prescribed path (tests/scenes/moving_pins.prm): at every
// step the pinned probe sits exactly on the path u = (0.05 sin 2πt, 0, 0.05 (1 - cos
// 2πt)) m (1e-12 m), and the free bottom corner is dragged along: it moves more than 1 cm
// in +x on the way (the pins reach 5 cm at t = 0.25 s) and more than 5 cm up by t = 0.5 s
// (pins: 10 cm).

#include <deal.II/base/mpi.h>

#include "app/application.h"
#include "csv.h"

#include <cmath>
#include <filesystem>
#include <iostream>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string                        output =
    std::filesystem::temp_directory_path() / "clothsim-moving-pins";
  const std::string scene =
    std::string(CLOTHSIM_SOURCE_DIR) + "/tests/scenes/moving_pins.prm";
  const char *arguments[] = {"clothsim", scene.c_str(), "--output-dir", output.c_str()};
  if (clothsim::run_application(4, arguments) != 0)
    return 1;

  const auto probes        = clothsim::test::read_csv(output + "/probes.csv");
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
  std::cout << "largest distance of the pin from its path " << worst_pin
            << " m; bottom corner: largest ux " << bottom_ux_max << " m, uz at t = 0.5 s "
            << bottom_uz << " m" << std::endl;
  const bool passed = worst_pin < 1e-12 && bottom_ux_max > 0.01 && bottom_uz > 0.05;
  std::cout << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
