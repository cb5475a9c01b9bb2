// Section "Output": VTK frames, probes and their closed-form references, progress line.

#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <deal.II/base/utilities.h>

#include "io/input_error.h"

#include <algorithm>

namespace clothsim
{
  namespace
  {
    // 'name: a, b, c; name2: ...' (Output/Probes, Output/Probe references): the pattern
    // and the parsed entries.
    Patterns::Map
    named_triples_pattern()
    {
      return Patterns::Map(Patterns::Anything(),
                           Patterns::List(Patterns::Double(), 3, 3, ","),
                           0,
                           1000,
                           ";",
                           ":");
    }

    std::vector<std::pair<std::string, Tensor<1, 3>>>
    parse_named_triples(const std::string &text)
    {
      std::vector<std::pair<std::string, Tensor<1, 3>>> entries;
      for (const std::string &item : Utilities::split_string_list(text, ';'))
        {
          const auto name_value = Utilities::split_string_list(item, ':');
          const auto v =
            Utilities::string_to_double(Utilities::split_string_list(name_value[1], ','));
          entries.emplace_back(name_value[0], Tensor<1, 3>({v[0], v[1], v[2]}));
        }
      return entries;
    }
  } // namespace


  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry(
      "Output interval",
      "0.0333333333333333",
      Patterns::Double(0., 1e9),
      "Simulated time in s between VTK frames and probe rows (0: every step). "
      "The first and last states are always written.");
    prm.declare_entry(
      "Drape disc radius",
      "0",
      Patterns::Double(0.),
      "m. With a positive radius R, statistics.csv gets the columns projected_area "
      "(m²: the cloth's shadow on the horizontal plane, folds counted once) and "
      "drape_coefficient, DC = (A_projected - π R²)/(A_specimen - π R²) with A_specimen "
      "the cloth's reference area (the Cusick drape test, ISO 9073-9: a specimen on a "
      "disc of radius R). 0: neither.");
    prm.declare_entry(
      "Check intersections",
      "false",
      Patterns::Bool(),
      "After every step, count the pairs of the cloth's triangles that share no "
      "vertex and intersect (touching counts): statistics.csv column "
      "intersecting_pairs. An independent check that the cloth does not pass "
      "through itself (physics/self_intersections.h states the tolerance). Costs a "
      "gather of the mesh on rank 0 and one pass of a bounding-volume hierarchy "
      "per step.");
    prm.declare_entry("Write VTK",
                      "true",
                      Patterns::Bool(),
                      "Write solution.pvd and its frames.");
    prm.declare_entry(
      "Probes",
      "",
      named_triples_pattern(),
      "Named reference points 'name: X, Y, Z; name2: X, Y, Z' (m). Each is located "
      "in the triangle of the (refined) reference surface closest to it; probes.csv "
      "records that triangle's closest point (X, Y, Z) and the displacement "
      "interpolated linearly there, and the log its distance from the point given. "
      "A point farther from the surface than 'Probe tolerance' allows is an error.");
    prm.declare_entry(
      "Probe tolerance",
      "0.01",
      Patterns::Double(0.),
      "How far a probe's point may lie from the (refined) reference surface, as a "
      "fraction of the mesh's longest edge (dimensionless). A point taken on a "
      "curved surface lies off its flat triangles by up to h²/(8R) for an edge h "
      "and a radius of curvature R: raise it for coarse meshes of curved surfaces.");
    prm.declare_entry(
      "Probe references",
      "",
      named_triples_pattern(),
      "Closed-form displacements 'probe: ux, uy, uz; ...' (m) of named probes at "
      "the end of the run (static mode: at full load), e.g. an elastica's tip. "
      "Convergence studies (clothsim --convergence) measure the probes' errors "
      "against them; runs ignore them.");
    prm.declare_entry(
      "Checkpoint interval",
      "0",
      Patterns::Double(0., 1e9),
      "Simulated time in s between checkpoints (0: none, except when the run is "
      "interrupted). A checkpoint, checkpoint.bin in the output directory, holds the "
      "run's whole state; clothsim --restart DIR continues the run from the last "
      "one, bit-identically. With a positive interval the end state is one too. "
      "Implicit integrators only, and not with 'Contact/Self contact = true' or "
      "'Self contact tangent = full pairs' ('creases' with vertex blocks is fine).");
    prm.declare_entry(
      "Progress",
      "auto",
      Patterns::Selection("auto|lines|off"),
      "Progress of the run (step, simulated time, elapsed time, ETA): 'auto' shows one "
      "updating line on a terminal, and otherwise (output to a file or pipe, any run "
      "under mpirun, whose ranks write to pseudo-terminals) a plain line every 5 % of "
      "the run, never a carriage return; 'lines' the plain lines always; 'off' "
      "nothing.");
    prm.leave_subsection();
  }

  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    interval            = prm.get_double("Output interval");
    write_vtk           = prm.get_bool("Write VTK");
    drape_disc_radius   = prm.get_double("Drape disc radius");
    check_intersections = prm.get_bool("Check intersections");
    probe_tolerance     = prm.get_double("Probe tolerance");
    probes.clear();
    for (const auto &[name, X] : parse_named_triples(prm.get("Probes")))
      probes.push_back({name, Point<3>(X), false, {}});
    for (const auto &[name, u] : parse_named_triples(prm.get("Probe references")))
      {
        const auto probe =
          std::find_if(probes.begin(), probes.end(), [&](const Probe &candidate) {
            return candidate.name == name;
          });
        if (probe == probes.end())
          throw InputError("",
                           "Output/Probe references",
                           "no probe named '" + name + "' in 'Output/Probes'");
        probe->has_reference          = true;
        probe->reference_displacement = u;
      }
    progress            = prm.get("Progress");
    checkpoint_interval = prm.get_double("Checkpoint interval");
    prm.leave_subsection();
  }
} // namespace clothsim
