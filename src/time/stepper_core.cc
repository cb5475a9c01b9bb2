#include "time/stepper_core.h"

#include <cmath>
#include <sstream>

namespace clothsim
{
  std::pair<double, double>
  StepTimes::since_last()
  {
    double assembly_total = 0., linear_total = 0.;
    for (const auto &[section, seconds] :
         timer.get_summary_data(TimerOutput::total_wall_time))
      if (section.rfind("assemble", 0) == 0)
        assembly_total += seconds;
      else if (section == "linear solve" || section == "preconditioner setup")
        linear_total += seconds;
    const std::pair<double, double> step = {assembly_total - assembly,
                                            linear_total - linear_solve};
    assembly                             = assembly_total;
    linear_solve                         = linear_total;
    return step;
  }


  StepperCore::StepperCore(const Parameters   &parameters,
                           ModelInterface     &model,
                           OutputWriter       &output,
                           ConditionalOStream &pcout,
                           TimerOutput        &timer)
    : parameters(parameters)
    , model(model)
    , output(output)
    , pcout(pcout)
    , timer(timer)
  {
    model.initialize_ghosted(u_ghosted);
    model.initialize_ghosted(v_ghosted);
  }


  void
  StepperCore::write_first_frame(const VectorType &u, const VectorType &v)
  {
    wall_clock.restart();
    model.import_ghosts(u, u_ghosted);
    model.import_ghosts(v, v_ghosted);
    dissipated       = 0.;
    prescribed       = 0.;
    strain_limited   = 0.;
    stiffness_raised = 0.;
    write_frame(0, 0.);
    const EnergyReport energies = current_energies();
    output.write_statistics({0,
                             0.,
                             0.,
                             0,
                             0,
                             0.,
                             0,
                             energies.kinetic,
                             energies.elastic,
                             energies.potential,
                             energies.columns,
                             0.});
  }


  std::string
  StepperCore::blow_up(const VectorType &u) const
  {
    const auto [smallest, largest] = model.area_ratio_range(u);
    if (smallest < 0.)
      return "NaN in the solution";
    if (!(smallest > 1e-6))
      return "a triangle collapsed (area ratio " + std::to_string(smallest) + ")";
    if (!(largest < 100.))
      return "a triangle grew " + std::to_string(largest) + " times its area";
    return "";
  }


  void
  StepperCore::limit_strain(const unsigned int step,
                            VectorType        &u,
                            VectorType        &v,
                            const double       dt)
  {
    if (!model.has_strain_limit())
      return;
    TimerOutput::Scope scope(timer, "strain limit");
    const auto         energy = [this, &u, &v]() {
      model.import_ghosts(u, u_ghosted);
      model.import_ghosts(v, v_ghosted);
      return model.mechanical_energy(u_ghosted, v_ghosted);
    };
    const double before             = energy();
    const auto [remaining, largest] = model.limit_strain(u, v, dt);
    strain_limited += energy() - before;
    if (remaining > 0)
      pcout << "step " << step << ": " << remaining
            << " springs still beyond the strain limit (largest strain " << largest
            << ") after " << parameters.mass_spring.strain_limit_iterations << " sweeps"
            << std::endl;
  }


  void
  StepperCore::set_increment(const VectorType &u_new, const VectorType &u_old)
  {
    if (increment.size() == 0)
      {
        model.initialize_ghosted(increment);
        model.initialize_ghosted(solved_ghosted);
      }
    VectorType difference(u_new);
    difference -= u_old;
    increment = difference;
  }


  void
  StepperCore::add_dissipation(const VectorType &solved,
                               const StepTerms  &terms,
                               const VectorType &u_new,
                               const VectorType &u_old)
  {
    if (!model.has_dissipation())
      return;
    TimerOutput::Scope scope(timer, "energy budget");
    set_increment(u_new, u_old);
    model.import_ghosts(solved, solved_ghosted);
    dissipated += model.dissipated_work(solved_ghosted, terms, increment);
  }


  void
  StepperCore::add_dissipation(const physics::RankVector &dissipative_gradient,
                               const VectorType          &u_new,
                               const VectorType          &u_old)
  {
    TimerOutput::Scope scope(timer, "energy budget");
    set_increment(u_new, u_old);
    dissipated += model.work(dissipative_gradient, increment);
  }


  void
  StepperCore::add_prescribed_work(const VectorType &solved,
                                   const StepTerms  &terms,
                                   const VectorType &u_new,
                                   const VectorType &u_old,
                                   const double      t_n,
                                   const double      t_new,
                                   const bool        trapezoid)
  {
    if (!model.has_prescribed_motion())
      return;
    TimerOutput::Scope scope(timer, "energy budget");
    if (start_ghosted.size() == 0)
      {
        model.initialize_ghosted(start_ghosted);
        model.initialize_ghosted(end_ghosted);
        model.initialize_owned(step_forces);
        if (solved_ghosted.size() == 0)
          model.initialize_ghosted(solved_ghosted);
      }
    // The pins: Σ_i F_i (u_new,i - u_old,i) over the constrained dofs that moved.
    const IndexSet                      &owned = model.owned_dofs();
    const MPI_Comm                       comm  = model.get_communicator();
    std::vector<types::global_dof_index> moved;
    for (const auto &line : model.get_constraints().get_lines())
      if (owned.is_element(line.index) && u_new[line.index] != u_old[line.index])
        moved.push_back(line.index);
    double work = 0.;
    if (Utilities::MPI::max(moved.size(), comm) > 0)
      {
        model.import_ghosts(solved, solved_ghosted);
        model.step_forces(solved_ghosted, terms, step_forces);
        const bool average = trapezoid && previous_forces.size() > 0;
        double     local   = 0.;
        for (const types::global_dof_index i : moved)
          local +=
            (average ? 0.5 * (previous_forces[i] + step_forces[i]) : step_forces[i]) *
            (u_new[i] - u_old[i]);
        work = Utilities::MPI::sum(local, comm);
        if (trapezoid)
          previous_forces = step_forces;
      }
    else
      previous_forces = VectorType(); // stale by the next move: that step starts afresh
    model.import_ghosts(u_old, start_ghosted);
    model.import_ghosts(u_new, end_ghosted);
    prescribed += work + model.obstacle_work(start_ghosted, end_ghosted, t_n, t_new);
  }


  void
  StepperCore::add_static_prescribed_work(const VectorType &u_new,
                                          const VectorType &u_old,
                                          const double      lambda_old,
                                          const double      lambda_new)
  {
    if (!model.has_prescribed_motion())
      return;
    // The static forces at the step's two equilibria, the reactions; at the first step
    // the start's, which a static state has without a solve.
    StepTerms terms;
    if (previous_forces.size() == 0)
      {
        TimerOutput::Scope scope(timer, "energy budget");
        terms.load_factor = terms.time = lambda_old;
        VectorType start;
        model.initialize_ghosted(start);
        model.import_ghosts(u_old, start);
        model.initialize_owned(previous_forces);
        model.step_forces(start, terms, previous_forces);
      }
    terms.load_factor = terms.time = lambda_new;
    add_prescribed_work(
      u_new, terms, u_new, u_old, lambda_old, lambda_new, /*trapezoid=*/true);
  }


  void
  StepperCore::record(const unsigned int  step,
                      const double        time,
                      const double        dt,
                      const StepFigures  &figures,
                      const EnergyReport &energies,
                      StepTimes          &step_times)
  {
    const auto spent = step_times.since_last();
    output.write_statistics({step,
                             time,
                             dt,
                             figures.newton_iterations,
                             figures.linear_iterations,
                             figures.residual,
                             figures.retries,
                             energies.kinetic,
                             energies.elastic,
                             energies.potential,
                             energies.columns,
                             wall_offset + wall_clock.wall_time(),
                             figures.rejected,
                             figures.error_estimate,
                             spent.first,
                             spent.second});
  }


  void
  StepperCore::write_frame(const unsigned int step, const double time)
  {
    TimerOutput::Scope scope(timer, "output");
    output.write_state(step, time, u_ghosted, [this]() {
      return model.output_fields(u_ghosted, v_ghosted);
    });
    const std::vector<SupportReaction> reactions =
      model.support_reactions(u_ghosted, time);
    if (!reactions.empty())
      output.write_reactions(step, time, reactions);
    frame_step = step;
    any_frame  = true;
  }


  void
  StepperCore::save_core(io::CheckpointData &run) const
  {
    run.set("core dissipated", dissipated);
    run.set("core prescribed work", prescribed);
    run.set("core strain limit energy", strain_limited);
    run.set("core stiffness raise energy", stiffness_raised);
    run.set("core frame step", frame_step);
    run.set("core any frame", any_frame ? 1. : 0.);
    run.set("core wall seconds", wall_offset + wall_clock.wall_time());
  }


  void
  StepperCore::restore_core(const io::CheckpointData &run)
  {
    dissipated = run.get_number("core dissipated");
    // Checkpoints before these were counted have none.
    for (const auto &[name, value] :
         {std::make_pair("core prescribed work", &prescribed),
          std::make_pair("core strain limit energy", &strain_limited),
          std::make_pair("core stiffness raise energy", &stiffness_raised)})
      *value = run.has(name) ? run.get_number(name) : 0.;
    frame_step  = static_cast<unsigned int>(run.get_number("core frame step"));
    any_frame   = run.get_number("core any frame") != 0.;
    wall_offset = run.get_number("core wall seconds");
    wall_clock.restart();
  }


  void
  StepperCore::stop_if_interrupted(const unsigned int           step,
                                   const double                 time,
                                   const std::function<void()> &checkpoint)
  {
    const int signal = received_signal(model.get_communicator());
    if (signal == 0)
      return;
    // The checkpoint first: the frame written for the interruption is not one the
    // uninterrupted run would write, and a restart replaces it.
    if (checkpoint)
      checkpoint();
    if (!any_frame || frame_step != step)
      write_frame(step, time);
    std::ostringstream message;
    message << "interrupted by " << signal_name(signal) << " after step " << step
            << " (t = " << time << "); its state is the last frame, and every file "
            << "written is complete";
    if (checkpoint)
      message << "; continue it with clothsim --restart " << output.get_directory();
    throw Interrupted(signal, message.str());
  }


  void
  StepperCore::check_step_floor(const double       dt,
                                const double       nominal,
                                const double       time,
                                const std::string &why) const
  {
    const double floor = parameters.time.minimum_step_fraction * nominal;
    if (dt >= floor)
      return;
    std::ostringstream message;
    message << why << " asks for dt = " << dt << " at t = " << time
            << ", below the floor " << floor << " ('Time/Minimum time step fraction' "
            << parameters.time.minimum_step_fraction << " x the step " << nominal
            << "): the run cannot make progress and stops here; output up to t = " << time
            << " is kept";
    throw SimulationError(message.str());
  }
} // namespace clothsim
