#pragma once

// Every run parameter, one struct per concept (declare_parameters / parse_parameters as
// in deal.II step-44). Units are in each entry's documentation; `clothsim
// --print-parameters` lists them all.

#include <deal.II/base/point.h>

#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler; // <deal.II/base/parameter_handler.h>, in the files that use it
}

namespace clothsim
{
  using namespace dealii;

  // The discretisation of the cloth's elasticity.
  enum class Model
  {
    fem,        // membrane (and shell bending) finite elements
    mass_spring // Provot's springs on the mesh's edges (physics/mass_spring.h)
  };

  struct SceneParameters
  {
    std::string  name; // output/<name>/; empty: the parameter file's stem
    Model        model;
    std::string  mesh_file;          // relative to the parameter file's directory
    unsigned int global_refinements; // uniform refinements of the mesh as read
    // Exact rest surface onto which refinement projects new vertices.
    std::string  surface;        // "flat" (none), "cylinder", "sphere"
    Point<3>     surface_center; // a point on the cylinder's axis, or the centre, m
    Tensor<1, 3> surface_axis;   // cylinder axis direction

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct MaterialParameters
  {
    double      stretch_stiffness; // E h, N/m (derived when given as E and thickness)
    double      poisson_ratio;     // dimensionless
    double      areal_density;     // kg/m²
    bool        lumped_mass;
    bool        bending;           // assemble the bending energy
    double      bending_rigidity;  // D, N·m (derived when given as E and thickness)
    std::string director_function; // "angle", "sine", "tangent" (see physics/bending.h)
    std::string preset; // a fabric preset's name (io/fabric_presets.h), or none
    // Orthotropic sheets (physics/sheet_stiffness.h): the warp's stiffness and rigidity
    // are stretch_stiffness and bending_rigidity, Poisson's ratio is ν_12.
    bool         orthotropic;
    double       weft_stretch_stiffness; // E_2 h, N/m
    double       shear_stiffness;        // G_12 h, N/m
    double       weft_bending_rigidity;  // D_2, N·m
    Tensor<1, 3> warp_direction;         // in space, m (any length)

    // `preset`: the fabric preset whose values are the defaults ("none": none).
    static void
    declare_parameters(ParameterHandler &prm, const std::string &preset = "none");
    void
    parse_parameters(ParameterHandler &prm);
  };

  // The mass-spring model's springs (used when Model = mass-spring).
  struct MassSpringParameters
  {
    bool         derived_constants;    // from Material (true) or given below (false)
    double       structural_stiffness; // N/m, given: every mesh edge
    double       shear_stiffness;      // N/m, given: across every interior edge
    double       bend_stiffness;       // N/m, given: across every interior edge
    double       bend_reference_angle; // rad, derived bend springs match the hinge here
    double       strain_limit;         // Provot's limit on (l - L)/L; 0: off
    bool         limit_compression;    // also keep (l - L)/L >= -limit
    unsigned int strain_limit_iterations; // correction sweeps per step

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct DampingParameters
  {
    double mass_proportional;      // α, 1/s: damping force -α M v
    double stiffness_proportional; // β, s:   damping force -β K v

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  // A load on the vertices of a point group (N per vertex) or along a boundary line
  // group (N per m of reference length).
  struct GroupLoad
  {
    std::string  name;
    Tensor<1, 3> value;
  };

  struct LoadParameters
  {
    Tensor<1, 3>           gravity;       // m/s²
    std::vector<GroupLoad> point_forces;  // N
    std::vector<GroupLoad> line_forces;   // N/m
    std::vector<GroupLoad> line_moments;  // N·m/m, about the group's edges
    std::vector<GroupLoad> point_moments; // N·m, couples on the vertices' triangles
    // 'fx; fy; fz' in x, y, z (N/m² of reference area); "0; 0; 0": none
    std::string surface_forces;
    double      pressure; // Pa, along the mesh normal of the current surface

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  // Air drag and wind (physics/air_drag.h); no air term while the density is 0.
  struct AirParameters
  {
    double      density;         // ρ_air, kg/m³
    double      normal_drag;     // C_n, dimensionless
    double      tangential_drag; // C_t, dimensionless
    std::string wind; // FunctionParser expressions 'wx; wy; wz' in m/s of (x, y, z, t)

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  // A mesh group whose vertices follow the pinned displacement in the given components.
  struct PinnedGroup
  {
    std::string         name;
    std::array<bool, 3> components; // x, y, z
    bool rotation = false; // 'r': the shell's rotation about the group's edges held
  };

  // A group whose rotation is held, turned by a prescribed rotation vector instead.
  struct PrescribedRotation
  {
    std::string name;
    std::string expressions; // 'θx; θy; θz' in rad, of x, y, z and t
  };

  struct ConstraintParameters
  {
    std::vector<PinnedGroup>        pinned_groups;
    std::vector<std::string>        clamped_groups; // boundary line groups
    std::vector<PrescribedRotation> prescribed_rotations;
    std::string pinned_displacement; // FunctionParser expression, x;y;z in m of (x,y,z,t)

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  enum class Integrator
  {
    backward_euler,
    static_load_steps,
    linear_static,       // one linear solve about the reference state
    arc_length,          // the equilibrium path by arc-length continuation
    symplectic_euler,    // explicit
    velocity_verlet,     // explicit
    bdf2,                // implicit, second order, variable step
    implicit_midpoint,   // implicit, second order, symplectic
    average_vector_field // implicit, second order, the midpoint rule conserving energy
  };

  // Static analyses: time is the load factor 0..1, no inertia.
  inline bool
  is_static(const Integrator integrator)
  {
    return integrator == Integrator::static_load_steps ||
           integrator == Integrator::linear_static ||
           integrator == Integrator::arc_length;
  }

  // The implicit midpoint rule and its energy-conserving variant solve for the step's
  // midpoint.
  inline bool
  solves_for_midpoint(const Integrator integrator)
  {
    return integrator == Integrator::implicit_midpoint ||
           integrator == Integrator::average_vector_field;
  }

  // Explicit integrators take no Newton solve: a step is a force evaluation.
  inline bool
  is_explicit(const Integrator integrator)
  {
    return integrator == Integrator::symplectic_euler ||
           integrator == Integrator::velocity_verlet;
  }

  struct TimeParameters
  {
    Integrator   integrator;
    double       end_time;  // s
    double       time_step; // s
    unsigned int max_step_halvings;
    double       minimum_step_fraction; // of the nominal step: the progress guard
    unsigned int load_steps;            // static mode: initial (or fixed) increments
    bool         adaptive_load_steps;   // static mode: grow increments that converge fast
    unsigned int maximum_arc_length_steps; // arc length: the path's longest run of steps
    // Adaptive time steps: local error estimate below tolerance + relative ||u||_inf.
    bool   adaptive_time_steps;
    double error_tolerance;          // m
    double relative_error_tolerance; // of the largest displacement
    double maximum_time_step;        // s
    // m; > 0: adaptive steps whose accepted local error estimates add up to at most
    // this over the run (error per unit step: each step's tolerance is target dt / T)
    double accuracy_target;
    // Initial state: FunctionParser expressions 'ux; uy; uz' in x, y, z (m, m/s).
    std::string initial_displacement;
    std::string initial_velocity;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  // How each step's nonlinear system is solved.
  enum class NewtonMethod
  {
    full,        // Newton iterations to the tolerances
    single_step, // one linearised step per time step (Baraff & Witkin 1998)
    inexact,     // linear tolerance from Eisenstat-Walker forcing terms
    modified     // a tangent serves several iterations (and steps)
  };

  struct NonlinearSolverParameters
  {
    NewtonMethod method;
    unsigned int jacobian_reuse;       // modified: most Newton iterations per tangent
    double       forcing_term_maximum; // inexact: largest linear relative tolerance
    unsigned int max_iterations;
    double       absolute_tolerance; // N
    double       relative_tolerance;
    std::string  line_search;          // "polynomial", "backtrack", "full step"
    std::string  tangent;              // "adaptive", "projected", "exact" (resolved)
    bool         mixed_stress_tangent; // membrane stress linearised (physics/membrane.h)
    double       displacement_tolerance;    // m
    double       truncation_error_fraction; // of the step's local error estimate
    std::string  truncation_error_norm;     // "largest" or "kinetic"
    bool         print_iterations;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct LinearSolverParameters
  {
    std::string  method;           // "cg", "gmres", "direct"
    std::string  direct_solver;    // "klu", "mumps"
    std::string  factor_precision; // "double", "single" (MUMPS' factors)
    std::string  preconditioner;   // "amg", "jacobi"
    double       relative_tolerance;
    unsigned int max_iterations;
    unsigned int amg_smoother_sweeps;
    double       amg_aggregation_threshold;
    bool         amg_reuse_aggregates;
    unsigned int amg_coarse_size;
    double       amg_chebyshev_range;
    std::string  amg_smoother; // "chebyshev", "block gauss-seidel" (finest level)

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct Probe
  {
    std::string name;
    Point<3>    reference_point; // m
    // A closed-form displacement at the end of the run (m), if the scene names one
    // ('Probe references'): convergence studies measure errors against it.
    bool         has_reference = false;
    Tensor<1, 3> reference_displacement;
  };

  struct OutputParameters
  {
    double             interval; // s; 0: every step
    bool               write_vtk;
    std::vector<Probe> probes;
    double             probe_tolerance;             // fraction of the longest edge
    std::string        progress;                    // "auto", "on", "off"
    double             drape_disc_radius;           // m; 0: no drape coefficient
    bool               check_intersections = false; // count intersecting triangle pairs
    double             checkpoint_interval = 0.;    // s; 0: only when interrupted

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  // A rigid obstacle (physics/obstacle.h), as given in a section "Obstacle k".
  struct ObstacleParameters
  {
    std::string  name;
    std::string  shape; // "plane", "sphere", "capsule", "disc", "box", "mesh"
    Point<3>     center;
    Tensor<1, 3> axis;
    double       radius;
    double       half_length;
    double       disc_radius;
    Tensor<1, 3> half_extents;
    double       friction;
    std::string  mesh_file;   // as given (relative to the parameter file)
    double       mesh_scale;  // m per unit of the mesh file
    std::string  translation; // 'x; y; z' expressions of t, m
    Tensor<1, 3> rotation_axis;
    std::string  rotation_angle; // an expression of t, rad
    double       removal_time;   // s; +inf: never removed
  };

  struct ContactParameters
  {
    static constexpr unsigned int max_obstacles = 8;

    double       thickness;                // d̂, m
    double       barrier_acceleration;     // a_b, m/s²
    bool         adaptive_stiffness;       // IPC's adaptive κ
    double       stiffening_distance;      // its trigger, a fraction of d̂
    double       max_barrier_acceleration; // its largest a_b, m/s²
    double       slip_velocity;            // ε_v, m/s
    bool         edge_contact;             // cloth edges/triangles vs core features
    std::string  edge_contact_tangent;     // automatic | gauss-newton | projected exact
    unsigned int friction_updates;         // solves per step
    bool         self_contact;             // the cloth with itself
    bool         self_contact_creases;     // only the pairs at each interior edge
    bool         self_contact_full_pairs;  // whole pair Hessians in the tangent
    double       self_friction;            // μ between layers of the cloth
    std::vector<ObstacleParameters> obstacles; // the sections in use

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  struct Parameters
  {
    SceneParameters           scene;
    MaterialParameters        material;
    MassSpringParameters      mass_spring;
    DampingParameters         damping;
    LoadParameters            loads;
    AirParameters             air;
    ConstraintParameters      constraints;
    TimeParameters            time;
    NonlinearSolverParameters nonlinear_solver;
    LinearSolverParameters    linear_solver;
    OutputParameters          output;
    ContactParameters         contact;

    // `preset`: the fabric preset whose values are the Material defaults.
    static void
    declare_parameters(ParameterHandler &prm, const std::string &preset = "none");
    void
    parse_parameters(ParameterHandler &prm);

    // Whether the scene moves something it prescribes: pins or held rotations given as
    // expressions of t, obstacles with a motion in t or a removal time. The work that
    // motion does on the cloth joins the energy balance (statistics.csv's
    // prescribed_work).
    bool
    prescribes_motion() const;
  };

  // Whether a FunctionParser expression reads the variable t (a token `t`, not a
  // function's name such as tan).
  bool
  mentions_time(const std::string &expression);

  // Every parameter as "Section/Name = default", its allowed values and its documentation
  // (units included), for clothsim --print-parameters; with `json`, one JSON object of
  // the sections, each entry an object {"default", "allowed", "documentation"}.
  void
  print_parameter_reference(std::ostream &out, const bool json = false);

  // The parameter file as read, with command-line overrides applied.
  struct ParameterInput
  {
    std::string              file;      // as given on the command line
    std::string              directory; // its directory, for relative paths in it
    std::vector<std::string> overrides; // "Section/Name=value"
    Parameters               parameters;
  };

  // Declares everything in `prm`, reads `file` (.prm or .json), applies `overrides`,
  // parses. Throws InputError naming the file (or "--set") and the entry on any problem.
  ParameterInput
  read_parameters(ParameterHandler               &prm,
                  const std::string              &file,
                  const std::vector<std::string> &overrides);
} // namespace clothsim
