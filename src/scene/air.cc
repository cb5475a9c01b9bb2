#include "scene/air.h"

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include "scene/boundary_conditions.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace clothsim
{
  namespace
  {
    // 'wx; wy; wz' as a function of (x, t), or none for '0; 0; 0'.
    physics::WindField
    make_wind(const std::string          &expressions,
              const std::string          &parameter_file,
              const mesh::Discretization &discretization)
    {
      const auto parts = Utilities::split_string_list(expressions, ';');
      if (std::all_of(parts.begin(), parts.end(), [](const std::string &part) {
            return part == "0";
          }))
        return {};
      auto wind = std::make_shared<FunctionParser<3>>(3);
      parse_vector_function(*wind, expressions, true, parameter_file, "Air/Wind");
      std::vector<std::pair<unsigned int, Point<3>>> samples;
      for (const auto &element : discretization.elements())
        {
          Point<3> centroid;
          for (const Point<3> &vertex : element.reference)
            centroid += vertex / 3.;
          for (unsigned int c = 0; c < 3; ++c)
            samples.emplace_back(c, centroid);
        }
      wind->set_time(0.);
      check_finite(*wind,
                   samples,
                   discretization.get_communicator(),
                   parameter_file,
                   "Air/Wind",
                   "triangle centroid");
      // The cell loop is serial: one parser, its time set before each evaluation.
      return [wind](const Point<3> &x, const double t) {
        wind->set_time(t);
        Tensor<1, 3> value;
        for (unsigned int c = 0; c < 3; ++c)
          value[c] = wind->value(x, c);
        return value;
      };
    }
  } // namespace


  std::unique_ptr<physics::AirDrag>
  make_air_drag(const AirParameters        &air,
                const std::string          &parameter_file,
                const mesh::Discretization &discretization)
  {
    return std::make_unique<physics::AirDrag>(
      physics::AirProperties{air.density, air.normal_drag, air.tangential_drag},
      make_wind(air.wind, parameter_file, discretization));
  }
} // namespace clothsim
