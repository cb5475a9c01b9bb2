#include "physics/contact_term.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "mesh/ghosted_values.h"
#include "physics/contact_potential.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace clothsim::physics
{
  namespace
  {
    std::string
    describe(const Point<3> &x)
    {
      std::ostringstream text;
      text << "(" << x[0] << ", " << x[1] << ", " << x[2] << ")";
      return text.str();
    }
  } // namespace


  void
  tangent_basis(const Tensor<1, 3> &n, Tensor<1, 3> (&t)[2])
  {
    Tensor<1, 3> helper;
    helper[std::abs(n[0]) < 0.9 ? 0 : 1] = 1.;
    t[0]                                 = helper - (helper * n) * n;
    t[0] /= t[0].norm();
    t[1] = cross_product_3d(n, t[0]);
  }


  ObstacleContact::ObstacleContact(std::vector<Obstacle>       obstacles,
                                   const ContactSettings      &settings,
                                   const mesh::Discretization &discretization,
                                   const VectorType           &lumped_masses)
    : AdaptiveBarrierTerm("contact",
                          settings.stiffness,
                          discretization.get_communicator())
    , obstacles(std::move(obstacles))
    , settings(settings)
    , discretization(discretization)
    , mesh_pairs(this->obstacles, this->settings, discretization, lumped_masses)
  {
    discretization.initialize_ghosted(step_start);
    // The owned vertices, in the order of their first triangle.
    for (const ClothSurface::Vertex &vertex : mesh_pairs.cloth_surface().vertices)
      if (vertex.owned)
        table.push_back(
          {vertex.dofs,
           vertex.local,
           vertex.reference,
           vertex.mass * settings.barrier_acceleration / settings.thickness});
  }


  std::vector<RigidPose>
  ObstacleContact::poses_at(const double time) const
  {
    std::vector<RigidPose> poses;
    for (const Obstacle &obstacle : obstacles)
      poses.push_back(obstacle.pose(time));
    return poses;
  }


  Point<3>
  ObstacleContact::position(const Vertex &vertex, const double *u_local) const
  {
    Point<3> x = vertex.reference;
    for (unsigned int c = 0; c < 3; ++c)
      x[c] += u_local[vertex.local[c]];
    return x;
  }


  double
  ObstacleContact::add_to_step(const VectorType                &u,
                               const StepTerms                 &step,
                               const AffineConstraints<double> &constraints,
                               VectorType                      *gradient,
                               MatrixType                      *hessian,
                               RankVector *) const
  {
    state_time            = step.time;
    const double  d_hat   = settings.thickness;
    const double  scale   = stiffness.scale();
    double        closest = std::numeric_limits<double>::infinity();
    const double *local = ghosted_values(u, discretization.relevant_dofs().n_elements());
    const std::vector<RigidPose> poses = poses_at(step.time);

    const bool            derivatives = gradient != nullptr || hessian != nullptr;
    double                value       = 0.;
    Vector<double>        g(3);
    FullMatrix<double>    H(3, 3);
    std::array<double, 9> hessian_rows;
    std::vector<types::global_dof_index> dofs(3);
    if (hessian != nullptr)
      vertex_scatter.start(*hessian, table.size(), 3);
    for (unsigned int k = 0; k < table.size(); ++k)
      {
        const Vertex  &vertex = table[k];
        const Point<3> x      = position(vertex, local);
        bool           near   = false;
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            if (is_mesh(o))
              continue;
            // The value alone first: most vertices are beyond d̂.
            const double distance = obstacles[o].distance(poses[o], x, false).value;
            closest               = std::min(closest, distance);
            if (distance >= d_hat)
              continue;
            value += scale * vertex.kappa * contact::barrier(distance, d_hat);
            if (!derivatives || distance <= 0.)
              continue;
            const SignedDistance d = obstacles[o].distance(poses[o], x, true);
            const double         first =
              scale * vertex.kappa * contact::barrier_first(d.value, d_hat);
            const double second =
              scale * vertex.kappa * contact::barrier_second(d.value, d_hat);
            if (!near) // the sums, zeroed only for the vertices within d̂
              {
                g = 0.;
                hessian_rows.fill(0.);
                near = true;
              }
            for (unsigned int i = 0; i < 3; ++i)
              {
                g[i] += first * d.gradient[i];
                for (unsigned int j = 0; j < 3; ++j)
                  // κ (s'' ∇d ∇dᵀ + s' ∇²d); s' <= 0 and ∇²d >= 0 make the second
                  // part negative semi-definite: the projected tangent drops it.
                  hessian_rows[3 * i + j] +=
                    second * d.gradient[i] * d.gradient[j] +
                    (step.projected_tangent ? 0. : first * d.hessian[i][j]);
              }
          }
        if (!near)
          continue;
        std::copy(vertex.dofs.begin(), vertex.dofs.end(), dofs.begin());
        if (gradient != nullptr)
          constraints.distribute_local_to_global(g, dofs, *gradient);
        if (hessian != nullptr &&
            !vertex_scatter.add(k, dofs, hessian_rows.data(), 3, constraints))
          {
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                H(i, j) = hessian_rows[3 * i + j];
            constraints.distribute_local_to_global(H, dofs, *hessian);
          }
      }
    if (!mesh_pairs.empty())
      {
        value += mesh_pairs.add_to_step(
          local, poses, step.projected_tangent, constraints, gradient, hessian);
        closest = std::min(closest, mesh_pairs.closest_assembled());
      }
    assembled_closest = closest;
    return value;
  }


  double
  ObstacleContact::energy(const VectorType &u, const VectorType &, RankVector *) const
  {
    StepTerms step;
    step.time = state_time;
    return add_to_step(u, step, AffineConstraints<double>(), nullptr, nullptr, nullptr);
  }


  double
  ObstacleContact::barrier_energy(const VectorType &u, const double time) const
  {
    // add_to_step records its time for energy() and the report; that stays the step's.
    const double kept = state_time;
    StepTerms    step;
    step.time = time;
    const double value =
      add_to_step(u, step, AffineConstraints<double>(), nullptr, nullptr, nullptr);
    state_time = kept;
    return value;
  }


  std::string
  ObstacleContact::begin_step(const double                     t_n,
                              const double                     t_new,
                              const VectorType                &u_n,
                              VectorType                      &u_new,
                              const AffineConstraints<double> &constraints)
  {
    last_dt = t_new - t_n;
    lagged.clear();
    ++n_lags;
    carried_points.assign(table.size() * obstacles.size(), Point<3>());
    const double                 d_hat = settings.thickness;
    const std::vector<RigidPose> start = poses_at(t_n), end = poses_at(t_new);
    start_poses = start;
    end_poses   = end;
    std::string failure;
    for (unsigned int k = 0; k < table.size() && failure.empty(); ++k)
      {
        const Vertex &vertex = table[k];
        Point<3>      x_n    = vertex.reference;
        Point<3>      guess  = vertex.reference;
        for (unsigned int c = 0; c < 3; ++c)
          {
            x_n[c] += u_n[vertex.dofs[c]];
            guess[c] += u_new[vertex.dofs[c]];
          }
        const Point<3> given = guess;
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            if (is_mesh(o))
              continue;
            const double d_n = obstacles[o].distance(start[o], x_n, false).value;
            if (d_n <= 0.)
              {
                failure = "the cloth vertex at " + describe(x_n) + " is on or inside " +
                          "obstacle '" + obstacles[o].name() +
                          "' at t = " + std::to_string(t_n) + " s";
                break;
              }
            // The start point carried along the obstacle's motion keeps d_n; the guess
            // is approached from there on the straight path in the obstacle's frame.
            const Point<3> carried = end[o].to_world(start[o].to_body(x_n));
            carried_points[k * obstacles.size() + o] = carried;
            const double alpha                       = obstacles[o].step_bound(end[o],
                                                         carried,
                                                         guess - carried,
                                                         settings.ccd_fraction);
            if (alpha < 1. && !constraints.is_constrained(vertex.dofs[0]))
              guess = carried + alpha * (guess - carried);
            // No friction from an obstacle that leaves within the step.
            if (d_n < d_hat && obstacles[o].friction() > 0. && end[o].present)
              {
                LaggedContact contact = vertex_contact(k, o, carried);
                tangent_basis(obstacles[o].distance(end[o], carried, true).gradient,
                              contact.tangent);
                contact.mu_lambda = obstacles[o].friction() * stiffness.scale() *
                                    vertex.kappa *
                                    std::abs(contact::barrier_first(d_n, d_hat));
                lagged.push_back(contact);
              }
          }
        if (!failure.empty() || guess == given)
          continue;
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          if (!is_mesh(o) && obstacles[o].distance(end[o], guess, false).value <= 0.)
            failure = "no start for the step to t = " + std::to_string(t_new) +
                      " s keeps the cloth vertex at " + describe(x_n) +
                      " outside every obstacle";
        for (unsigned int c = 0; c < 3; ++c)
          u_new[vertex.dofs[c]] = guess[c] - vertex.reference[c];
      }
    u_new.compress(VectorOperation::insert);
    failure = first_message(failure);
    if (failure.empty() && !mesh_pairs.empty())
      failure = first_message(begin_mesh_step(u_n, u_new, constraints));
    if (failure.empty() && !mesh_pairs.empty())
      failure = ride_along(t_new, u_n, u_new, constraints);
    return failure;
  }


  LaggedContact
  ObstacleContact::vertex_contact(const unsigned int k,
                                  const unsigned int o,
                                  const Point<3>    &carried) const
  {
    LaggedContact contact;
    contact.obstacle  = o;
    contact.vertex    = k;
    contact.n_points  = 1;
    contact.points[0] = {table[k].dofs,
                         table[k].local,
                         table[k].reference,
                         1.,
                         carried,
                         true,
                         table[k].local};
    return contact;
  }


  std::string
  ObstacleContact::first_message(const std::string &local) const
  {
    // The message of the lowest rank that has one.
    const MPI_Comm     communicator = discretization.get_communicator();
    const unsigned int rank         = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int first =
      Utilities::MPI::min(local.empty() ? std::numeric_limits<unsigned int>::max() : rank,
                          communicator);
    if (first == std::numeric_limits<unsigned int>::max())
      return "";
    return Utilities::MPI::broadcast(communicator, local, first);
  }


  std::string
  ObstacleContact::penetration(const VectorType &u, const double time) const
  {
    const std::vector<RigidPose> poses = poses_at(time);
    std::string                  found;
    for (const Vertex &vertex : table)
      {
        Point<3> x = vertex.reference;
        for (unsigned int c = 0; c < 3; ++c)
          x[c] += u[vertex.dofs[c]];
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            if (is_mesh(o))
              continue;
            const double d = obstacles[o].distance(poses[o], x, false).value;
            if (d <= 0. && found.empty())
              found = "the cloth vertex at " + describe(x) +
                      " is on or inside obstacle '" + obstacles[o].name() +
                      "' (d = " + std::to_string(d) +
                      " m) at t = " + std::to_string(time) + " s";
          }
      }
    if (found.empty() && !mesh_pairs.empty())
      {
        VectorType ghosted;
        discretization.initialize_ghosted(ghosted);
        discretization.import_ghosts(u, ghosted);
        found = mesh_pairs.touching(
          ghosted_values(ghosted, discretization.relevant_dofs().n_elements()), poses);
        if (!found.empty())
          found += " at t = " + std::to_string(time) + " s";
      }
    return first_message(found);
  }


  double
  ObstacleContact::relag_friction(const VectorType &u)
  {
    const double  d_hat = settings.thickness;
    const double *local = ghosted_values(u, discretization.relevant_dofs().n_elements());
    const unsigned int  n_obstacles = obstacles.size();
    std::vector<double> before(table.size() * n_obstacles, 0.);
    std::vector<double> mesh_before;
    for (const LaggedContact &contact : lagged)
      if (contact.vertex != numbers::invalid_unsigned_int)
        before[contact.vertex * n_obstacles + contact.obstacle] = contact.mu_lambda;
      else
        mesh_before.push_back(contact.mu_lambda);
    lagged.clear();
    ++n_lags;
    double largest = 0., change = 0.;
    for (unsigned int k = 0; k < table.size(); ++k)
      for (unsigned int o = 0; o < n_obstacles; ++o)
        {
          if (is_mesh(o))
            continue;
          const Point<3>                x = position(table[k], local);
          const physics::SignedDistance d = obstacles[o].distance(end_poses[o], x, true);
          double                        mu_lambda = 0.;
          if (d.value < d_hat && obstacles[o].friction() > 0.)
            {
              LaggedContact contact =
                vertex_contact(k, o, carried_points[k * n_obstacles + o]);
              tangent_basis(d.gradient, contact.tangent);
              mu_lambda = contact.mu_lambda =
                obstacles[o].friction() * stiffness.scale() * table[k].kappa *
                std::abs(contact::barrier_first(d.value, d_hat));
              lagged.push_back(contact);
            }
          largest = std::max({largest, mu_lambda, before[k * n_obstacles + o]});
          change  = std::max(change, std::abs(mu_lambda - before[k * n_obstacles + o]));
        }
    if (!mesh_pairs.empty())
      {
        // Pairs have no lasting identity: compare the sorted forces.
        const std::size_t  first = lagged.size();
        const unsigned int n     = discretization.relevant_dofs().n_elements();
        const double      *start = ghosted_values(step_start, n);
        mesh_pairs.lag_friction(
          local, std::vector<double>(start, start + n), start_poses, end_poses, lagged);
        std::vector<double> after;
        for (std::size_t k = first; k < lagged.size(); ++k)
          after.push_back(lagged[k].mu_lambda);
        std::sort(mesh_before.begin(), mesh_before.end());
        std::sort(after.begin(), after.end());
        mesh_before.resize(std::max(mesh_before.size(), after.size()), 0.);
        after.resize(mesh_before.size(), 0.);
        for (std::size_t k = 0; k < after.size(); ++k)
          {
            largest = std::max({largest, after[k], mesh_before[k]});
            change  = std::max(change, std::abs(after[k] - mesh_before[k]));
          }
      }
    const MPI_Comm communicator = discretization.get_communicator();
    largest                     = Utilities::MPI::max(largest, communicator);
    change                      = Utilities::MPI::max(change, communicator);
    return largest > 0. ? change / largest : 0.;
  }


  double
  ObstacleContact::largest_step(const VectorType &u,
                                const VectorType &direction,
                                const double      time) const
  {
    const unsigned int           n_relevant = discretization.relevant_dofs().n_elements();
    const double                *local      = ghosted_values(u, n_relevant);
    const double                *step       = ghosted_values(direction, n_relevant);
    const std::vector<RigidPose> poses      = poses_at(time);
    double                       alpha      = vertex_step_bound(local, step, poses);
    if (!mesh_pairs.empty())
      alpha =
        std::min(alpha,
                 mesh_pairs.largest_step(local, step, poses, settings.ccd_fraction));
    return Utilities::MPI::min(alpha, discretization.get_communicator());
  }


  double
  ObstacleContact::vertex_step_bound(const double                 *local,
                                     const double                 *step,
                                     const std::vector<RigidPose> &poses) const
  {
    double alpha = 1.;
    for (const Vertex &vertex : table)
      {
        const Point<3> x = position(vertex, local);
        Tensor<1, 3>   dx;
        for (unsigned int c = 0; c < 3; ++c)
          dx[c] = step[vertex.local[c]];
        const double length = dx.norm();
        if (length == 0.)
          continue;
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            if (is_mesh(o))
              continue;
            const double d = obstacles[o].distance(poses[o], x, false).value;
            // 1-Lipschitz: far enough that the full step cannot come near.
            if (d - length > settings.ccd_fraction * d)
              continue;
            alpha =
              std::min(alpha,
                       obstacles[o].step_bound(poses[o], x, dx, settings.ccd_fraction));
          }
      }
    return alpha;
  }


  ObstacleContact::Report
  ObstacleContact::report(const VectorType &u, const double time) const
  {
    const double *local = ghosted_values(u, discretization.relevant_dofs().n_elements());
    const std::vector<RigidPose> poses  = poses_at(time);
    Report                       result = local_report(local, poses);
    result.min_surface_distance         = result.min_distance;
    lower_to_surface_distance(local, poses, result.min_surface_distance);
    const MPI_Comm communicator = discretization.get_communicator();
    result.min_distance         = Utilities::MPI::min(result.min_distance, communicator);
    result.min_surface_distance =
      Utilities::MPI::min(result.min_surface_distance, communicator);
    for (unsigned int o = 0; o < obstacles.size(); ++o)
      {
        for (unsigned int c = 0; c < 3; ++c)
          result.forces[o][c] = Utilities::MPI::sum(result.forces[o][c], communicator);
        result.contacts[o] = Utilities::MPI::sum(result.contacts[o], communicator);
      }
    return result;
  }


  ObstacleContact::Report
  ObstacleContact::local_report(const double                 *local,
                                const std::vector<RigidPose> &poses) const
  {
    Report result{std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity(),
                  std::vector<Tensor<1, 3>>(obstacles.size()),
                  std::vector<unsigned int>(obstacles.size(), 0)};
    for (const Vertex &vertex : table)
      {
        const Point<3> x = position(vertex, local);
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            if (is_mesh(o))
              continue;
            const SignedDistance d = obstacles[o].distance(poses[o], x, true);
            result.min_distance    = std::min(result.min_distance, d.value);
            if (d.value >= settings.thickness)
              continue;
            ++result.contacts[o];
            // The force on the cloth, -κ s'(d) ∇d (outward).
            result.forces[o] -= stiffness.scale() * vertex.kappa *
                                contact::barrier_first(d.value, settings.thickness) *
                                d.gradient;
          }
      }
    if (!mesh_pairs.empty())
      mesh_pairs.report(
        local, poses, result.min_distance, result.forces, result.contacts);
    return result;
  }


  double
  ObstacleContact::closest_at_start(const VectorType &u, const double time) const
  {
    const double *local = ghosted_values(u, discretization.relevant_dofs().n_elements());
    return Utilities::MPI::min(local_report(local, poses_at(time)).min_distance,
                               discretization.get_communicator());
  }


  void
  ObstacleContact::lower_to_surface_distance(const double                 *u_local,
                                             const std::vector<RigidPose> &poses,
                                             double &min_distance) const
  {
    const double        tolerance = 1e-3 * settings.thickness;
    const ClothSurface &surface   = mesh_pairs.cloth_surface();
    for (const std::array<unsigned int, 3> &triangle : surface.triangles)
      {
        const std::array<Point<3>, 3> x = {{surface.position(triangle[0], u_local),
                                            surface.position(triangle[1], u_local),
                                            surface.position(triangle[2], u_local)}};
        const double longest            = std::sqrt(std::max({x[0].distance_square(x[1]),
                                                              x[1].distance_square(x[2]),
                                                              x[2].distance_square(x[0])}));
        for (unsigned int o = 0; o < obstacles.size(); ++o)
          {
            // A plane's distance is smallest at a corner, which report() has seen.
            const ObstacleCore core = obstacles[o].shape().core;
            if (core == ObstacleCore::mesh || core == ObstacleCore::half_space)
              continue;
            // d is 1-Lipschitz: no point of the triangle is closer than its nearest
            // corner minus its longest edge. And d is convex (the obstacle is): where it
            // is differentiable, outside, its tangent plane at a corner lies below it,
            // d(p) >= d_i + ∇d_i·(p - x_i), which is least over the triangle at a corner
            // (exact where d is affine: a triangle on a flat face).
            std::array<SignedDistance, 3> at;
            double corner = std::numeric_limits<double>::infinity();
            for (unsigned int i = 0; i < 3; ++i)
              {
                at[i]  = obstacles[o].distance(poses[o], x[i], true);
                corner = std::min(corner, at[i].value);
              }
            double bound = corner - longest;
            if (corner > 0.)
              for (unsigned int i = 0; i < 3; ++i)
                {
                  double least = 0.;
                  for (unsigned int j = 0; j < 3; ++j)
                    least = std::min(least, at[i].gradient * (x[j] - x[i]));
                  bound = std::max(bound, at[i].value + least);
                }
            if (bound >= min_distance)
              continue;
            min_distance =
              std::min(min_distance,
                       obstacles[o].triangle_distance(poses[o], x, tolerance));
          }
      }
  }


} // namespace clothsim::physics
