// Sections "Contact" and "Obstacle 1" ... "Obstacle 8": rigid obstacles the cloth
// touches.

#include <deal.II/base/utilities.h>

#include "io/input_error.h"
#include "io/parameters.h"

#include "io/parameters_detail.h"
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace clothsim
{
  using detail::vector_entry;

  namespace
  {
    std::string
    section(const unsigned int k)
    {
      return "Obstacle " + std::to_string(k + 1);
    }

    // 'never' (+inf) or a time >= 0 (s).
    double
    removal_time(const std::string &given, const std::string &where)
    {
      if (given == "never")
        return std::numeric_limits<double>::infinity();
      std::istringstream text(given);
      double             time = 0.;
      if (!(text >> time) || !(text >> std::ws).eof() || !(time >= 0.) ||
          !std::isfinite(time))
        throw InputError("",
                         where + "/Removed at",
                         "'" + given + "' is neither 'never' nor a time >= 0 in s");
      return time;
    }
  } // namespace


  void
  ContactParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("Thickness",
                      "0.005",
                      Patterns::Double(1e-9, 1.),
                      "Contact thickness d̂ in m: a cloth vertex closer than this to an "
                      "obstacle is pushed away by a barrier that grows without bound as "
                      "the distance goes to zero (IPC's log barrier). Resting cloth sits "
                      "within it, so it is the visible gap.");
    prm.declare_entry("Barrier stiffness",
                      "100",
                      Patterns::Double(1e-6, 1e12),
                      "a_b in m/s²: a vertex of mass m pays m a_b/d̂ times the barrier "
                      "s(d) = -(d - d̂)² ln(d/d̂), so at d = d̂/2 it is pushed with 1.19 m "
                      "a_b. A vertex resting under gravity g sits where 3 (1 - d/d̂)² is "
                      "about g/a_b (at 0.82 d̂ for the default).");
    prm.declare_entry(
      "Adaptive barrier stiffness",
      "false",
      Patterns::Bool(),
      "IPC's adaptive stiffness (Li et al. 2020): after each Newton iterate whose "
      "closest pair (a cloth vertex or pair against an obstacle; for self-contact, "
      "two parts of the cloth) is nearer than 'Stiffening distance' times "
      "'Thickness' and nearer than at the iterate before, the barrier stiffness of "
      "that contact (obstacles, or self-contact) doubles, up to 'Maximum barrier "
      "stiffness'. A step's retry (after a failed Newton solve or a rejected "
      "step) starts again from the stiffness the last accepted step ended with; "
      "otherwise it is never lowered (checkpoints keep it). For "
      "impacts whose forces would press a pair towards round-off, where Newton's "
      "step cap stalls (README, Contact with obstacles). Needs the energy line "
      "search (not 'Line search = full step').");
    prm.declare_entry("Stiffening distance",
                      "0.001",
                      Patterns::Double(1e-12, 1.),
                      "With 'Adaptive barrier stiffness': the distance below which a "
                      "closing pair doubles the barrier stiffness, as a fraction of "
                      "'Thickness'.");
    prm.declare_entry("Maximum barrier stiffness",
                      "1e6",
                      Patterns::Double(1e-6, 1e15),
                      "With 'Adaptive barrier stiffness': the largest a_b (m/s²) it "
                      "raises the stiffness to; at least 'Barrier stiffness'.");
    prm.declare_entry("Static friction velocity",
                      "1e-3",
                      Patterns::Double(1e-12, 1e3),
                      "ε_v in m/s: below this slip velocity friction is static (a stiff "
                      "spring), above it kinetic (μ times the normal force).");
    prm.declare_entry(
      "Edge contact",
      "true",
      Patterns::Bool(),
      "Whether the cloth's edges and triangles meet the sharp or narrow parts of the "
      "analytic obstacles (a sphere's centre, a capsule's segment, a box's corners and "
      "edges, a disc's rim), each by IPC's pairs at their distance less 'Radius', "
      "besides its vertices meeting every obstacle's surface. Without it a sphere, "
      "rod, rim or box edge narrower than the cloth's triangles passes between the "
      "vertices: up to h²/(8 r) into an obstacle of radius r under triangles of edge "
      "h, or right through a thin rod. Planes need no edge contact; mesh obstacles "
      "always have it. Measured (README, Contact with obstacles): 1.1 to 1.3 times "
      "the run time of the shipped scenes. How its pairs enter Newton's tangent: "
      "'Edge contact tangent'.");
    prm.declare_entry(
      "Edge contact tangent",
      "automatic",
      Patterns::Selection("automatic|gauss-newton|projected exact"),
      "How edge contact's pairs enter Newton's tangent. 'gauss-newton': κ s''(d) ∇d "
      "∇dᵀ. 'projected exact': the exact Hessian with its negative eigenvalues set to "
      "zero, which keeps the stiffness κ |s'(d)| (d + r) against a cloth triangle or "
      "edge turning about its closest point to a core of radius r (Gauss-Newton drops "
      "it). 'automatic': 'projected exact' for an obstacle whose core moves by more "
      "than half its 'Radius' within a 'Time step' (with 'Adaptive time steps', within "
      "'Maximum time step' if longer) somewhere in the run (the run's log names it), "
      "'gauss-newton' for the others. Measured (README, Contact with "
      "obstacles): with 'gauss-newton' a sphere moving by its radius or more per step "
      "makes Newton turn triangles into it and stall on the pairs' step cap; "
      "'projected exact' costs 1.2 to 1.4 times as much per Newton iteration on the "
      "shipped scenes, whose obstacles do not move that fast.");
    prm.declare_entry(
      "Friction updates",
      "1",
      Patterns::Integer(1, 100),
      "1: friction's normal forces and tangent planes are lagged from the "
      "step's start (IPC). k > 1: after each converged solve they are taken "
      "again at the solution and the step is solved again, until they "
      "change by less than 0.1 % of the largest or after k solves.");
    prm.declare_entry(
      "Self contact",
      "false",
      Patterns::Selection("false|true|creases"),
      "The cloth against itself. 'true': every vertex-triangle and edge-edge pair "
      "that shares no vertex pays the same barrier within 'Thickness', and the line "
      "search never lets the cloth pass through itself. 'creases': only the pairs of "
      "the two triangles at each interior edge (each one's opposite vertex against "
      "the other, each one's other edges against the other's): a crease cannot close "
      "through itself (where 'Material/Director function = angle' jumps), at a "
      "fraction of the cost, but other parts of the cloth may still pass through "
      "each other. 'Thickness' must be below the smallest such distance at rest "
      "(checked). Works under MPI (every rank holds the whole surface).");
    prm.declare_entry(
      "Self friction",
      "0",
      Patterns::Double(0.),
      "Coulomb's friction coefficient μ between layers of the cloth "
      "(with 'Self contact'), lagged once per step as with the obstacles.");
    prm.declare_entry(
      "Self contact tangent",
      "vertex blocks",
      Patterns::Selection("vertex blocks|full pairs"),
      "How a self-contact pair's Hessian enters Newton's tangent. 'vertex "
      "blocks': its 3 x 3 blocks on each vertex only (block Jacobi; the tangent "
      "keeps the mesh's sparsity). 'full pairs': all of it, coupling vertices "
      "that share no triangle; the sparsity grows with the pairs before each step "
      "and the direct solver analyses it again. Measured (README, Self-contact): "
      "'vertex blocks' is faster on the shipped scenes, with about as many Newton "
      "iterations.");
    prm.leave_subsection();

    for (unsigned int k = 0; k < max_obstacles; ++k)
      {
        prm.enter_subsection(section(k));
        prm.declare_entry("Shape",
                          "none",
                          Patterns::Selection("none|plane|sphere|capsule|disc|box|mesh"),
                          "'plane' (the half-space below it is solid), 'sphere', "
                          "'capsule' (a cylinder with round ends), 'disc' (a round flat "
                          "plate with rounded rim, e.g. a table top), 'box' (edges "
                          "rounded by 'Radius'), 'mesh' (a triangle surface read from "
                          "'Mesh file'; sharp edges and corners are fine); 'none': this "
                          "section is unused.");
        prm.declare_entry("Name",
                          "",
                          Patterns::Anything(),
                          "For the output; default 'obstacle k'.");
        prm.declare_entry("Center",
                          "0, 0, 0",
                          Patterns::List(Patterns::Double(), 3, 3, ","),
                          "m: a point on the plane; the centre of the other shapes.");
        prm.declare_entry("Axis",
                          "0, 0, 1",
                          Patterns::List(Patterns::Double(), 3, 3, ","),
                          "The plane's normal (pointing out of the solid), the capsule's "
                          "axis, the disc's normal; need not be unit.");
        prm.declare_entry("Radius",
                          "0",
                          Patterns::Double(0.),
                          "m: of the sphere and the capsule; the rounding of the disc's "
                          "rim (half its thickness) and of the box's edges.");
        prm.declare_entry("Half length",
                          "0",
                          Patterns::Double(0.),
                          "m: half the length of the capsule's axis segment.");
        prm.declare_entry("Disc radius", "0", Patterns::Double(0.), "m: of the disc.");
        prm.declare_entry("Half extents",
                          "0, 0, 0",
                          Patterns::List(Patterns::Double(0.), 3, 3, ","),
                          "m: of the box's core along x, y, z (the box is that plus "
                          "'Radius' on every side).");
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "The triangle surface of a 'mesh' obstacle, relative to this "
                          "parameter file's directory: gmsh (.msh, or .geo meshed on "
                          "reading), STL (ASCII or binary) or OBJ. Its coordinates are "
                          "the obstacle's position at t = 0 (times 'Mesh scale'); "
                          "'Center' is the centre of its rotation. Need not be closed.");
        prm.declare_entry("Mesh scale",
                          "1",
                          Patterns::Double(1e-12),
                          "Multiplies the mesh file's coordinates to give m (0.001 for a "
                          "file in mm).");
        prm.declare_entry("Friction",
                          "0",
                          Patterns::Double(0.),
                          "Coulomb's friction coefficient μ against the cloth.");
        prm.declare_entry("Translation",
                          "0; 0; 0",
                          Patterns::List(Patterns::Anything(), 3, 3, ";"),
                          "Prescribed motion: 'x; y; z' in m as expressions of t (s), "
                          "e.g. '0; 0; -0.5*t'.");
        prm.declare_entry("Rotation axis",
                          "0, 0, 1",
                          Patterns::List(Patterns::Double(), 3, 3, ","),
                          "The axis, through 'Center', of the prescribed rotation.");
        prm.declare_entry("Rotation angle",
                          "0",
                          Patterns::Anything(),
                          "rad, an expression of t (s), e.g. '2*t'; a constant turns a "
                          "box.");
        prm.declare_entry("Removed at",
                          "never",
                          Patterns::Anything(),
                          "s, or 'never': the obstacle leaves the scene at this time "
                          "(a support taken away). The steps that end after it see no "
                          "barrier, cap or friction of it, and it carries no cloth "
                          "along as it goes.");
        prm.leave_subsection();
      }
  }


  void
  ContactParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    thickness                = prm.get_double("Thickness");
    barrier_acceleration     = prm.get_double("Barrier stiffness");
    adaptive_stiffness       = prm.get_bool("Adaptive barrier stiffness");
    stiffening_distance      = prm.get_double("Stiffening distance");
    max_barrier_acceleration = prm.get_double("Maximum barrier stiffness");
    if (adaptive_stiffness && max_barrier_acceleration < barrier_acceleration)
      throw InputError("",
                       "Contact/Maximum barrier stiffness",
                       "is below 'Barrier stiffness' (" +
                         std::to_string(barrier_acceleration) + " m/s²)");
    slip_velocity           = prm.get_double("Static friction velocity");
    friction_updates        = prm.get_integer("Friction updates");
    edge_contact            = prm.get_bool("Edge contact");
    edge_contact_tangent    = prm.get("Edge contact tangent");
    self_contact            = prm.get("Self contact") != "false";
    self_contact_creases    = prm.get("Self contact") == "creases";
    self_contact_full_pairs = prm.get("Self contact tangent") == "full pairs";
    self_friction           = prm.get_double("Self friction");
    prm.leave_subsection();

    obstacles.clear();
    for (unsigned int k = 0; k < max_obstacles; ++k)
      {
        prm.enter_subsection(section(k));
        ObstacleParameters obstacle;
        obstacle.shape = prm.get("Shape");
        if (obstacle.shape != "none")
          {
            obstacle.name = prm.get("Name");
            if (obstacle.name.empty())
              obstacle.name = "obstacle " + std::to_string(k + 1);
            obstacle.center         = Point<3>(vector_entry(prm.get("Center")));
            obstacle.axis           = vector_entry(prm.get("Axis"));
            obstacle.radius         = prm.get_double("Radius");
            obstacle.half_length    = prm.get_double("Half length");
            obstacle.disc_radius    = prm.get_double("Disc radius");
            obstacle.half_extents   = vector_entry(prm.get("Half extents"));
            obstacle.friction       = prm.get_double("Friction");
            obstacle.mesh_file      = prm.get("Mesh file");
            obstacle.mesh_scale     = prm.get_double("Mesh scale");
            obstacle.translation    = prm.get("Translation");
            obstacle.rotation_axis  = vector_entry(prm.get("Rotation axis"));
            obstacle.rotation_angle = prm.get("Rotation angle");
            const std::string where = section(k);
            obstacle.removal_time   = removal_time(prm.get("Removed at"), where);
            if (obstacle.axis.norm() == 0.)
              throw InputError("", where + "/Axis", "must not be zero");
            if (obstacle.rotation_axis.norm() == 0.)
              throw InputError("", where + "/Rotation axis", "must not be zero");
            const bool needs_radius =
              obstacle.shape == "sphere" || obstacle.shape == "capsule";
            if (needs_radius && obstacle.radius <= 0.)
              throw InputError("",
                               where + "/Radius",
                               "a " + obstacle.shape + " needs a positive radius");
            if (obstacle.shape == "disc" && obstacle.disc_radius <= 0.)
              throw InputError("",
                               where + "/Disc radius",
                               "a disc needs a positive radius");
            if (obstacle.shape == "mesh" && obstacle.mesh_file.empty())
              throw InputError("",
                               where + "/Mesh file",
                               "a mesh obstacle needs its surface's file");
            if (obstacle.shape == "box" &&
                obstacle.half_extents[0] + obstacle.radius <= 0.)
              throw InputError("", where + "/Half extents", "a box needs a size");
            obstacles.push_back(obstacle);
          }
        prm.leave_subsection();
      }
  }
} // namespace clothsim
