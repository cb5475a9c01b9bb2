// Section "Air": air drag and wind (physics/air_drag.h).

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

namespace clothsim
{
  void
  AirParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Air");
    prm.declare_entry(
      "Density",
      "0",
      Patterns::Double(0., 1e4),
      "Density of the air rho_air in kg/m³ (1.2 is air at 20 °C and sea level); 0: no "
      "air term. Drag per triangle of area A (m²) and normal n, at the velocity v_r "
      "(m/s) of the triangle relative to the wind: f = -1/2 rho_air A (C_n |v_n| v_n n "
      "+ C_t |v_t| v_t), v_n = v_r.n, v_t = v_r - v_n n; a dissipative term of the "
      "implicit step (physics/air_drag.h). Needs 'Time/Integrator' backward euler, "
      "bdf2 or implicit midpoint.");
    prm.declare_entry(
      "Normal drag coefficient",
      "1.2",
      Patterns::Double(0., 100.),
      "C_n, dimensionless: drag of the flow across the cloth, a flat plate face-on "
      "(measured 1.17 for a disc, 1.18 to 1.28 for squares and rectangles at "
      "Reynolds numbers above 1e4).");
    prm.declare_entry(
      "Tangential drag coefficient",
      "0.02",
      Patterns::Double(0., 100.),
      "C_t, dimensionless: skin friction of the flow along the cloth, both faces "
      "together (a smooth plate in turbulent flow at Reynolds number 1e6 gives 2 x "
      "0.0047; woven fabric is rougher).");
    prm.declare_entry(
      "Wind",
      "0; 0; 0",
      Patterns::List(Patterns::Anything(), 3, 3, ";"),
      "Wind velocity in m/s: three expressions 'wx; wy; wz' in the coordinates x, y, "
      "z (m) of a triangle's centroid at the step's start and the time t (s), e.g. "
      "'8; 0; 0' or '8*(1 + 0.5*sin(2*pi*t)); 0; 0'.");
    prm.leave_subsection();
  }

  void
  AirParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Air");
    density         = prm.get_double("Density");
    normal_drag     = prm.get_double("Normal drag coefficient");
    tangential_drag = prm.get_double("Tangential drag coefficient");
    wind            = prm.get("Wind");
    prm.leave_subsection();
  }
} // namespace clothsim
