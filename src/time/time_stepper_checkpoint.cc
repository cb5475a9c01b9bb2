// The implicit stepper's checkpoints (io/checkpoint.h): everything its loop carries from
// one step to the next, so that a restart continues bit-identically. A checkpoint is
// taken at the top of the loop of sub-steps (after an accepted step, or where an
// interruption stops the run), and a restart enters that loop there:
//   vectors     u_n, v_n; BDF2's u_{n-1}, v_{n-1}; the static mode's last increment
//               (owned entries, in the order of the owned dofs)
//   step        the last step's size (BDF2's ratio, the error estimate), the step
//   control     controller (nominal step, target, proposed step, halvings, rejections,
//               carried halvings, the step's span), the loop's time, step number, next
//               output and checkpoint times, Newton's last iterations, failed attempts,
//               the run's totals
//   solver      MUMPS' choice of factorisation. The tangent kept by 'modified newton'
//               and the AMG aggregates are not stored: the run renews them after each
//               checkpoint (NewtonSolver::renew), as the restart starts without them
//   model       the terms' carried state (director references) and the mesh's
//               fingerprint (ModelInterface::save_state)
//   output      the frames and CSV bytes written (OutputWriter::save), the dissipated
//               work and frame bookkeeping (StepperCore::save_core)

#include "time/time_stepper.h"

namespace clothsim
{
  namespace
  {
    // The owned entries of a vector.
    std::vector<double>
    owned_values(const VectorType &vector)
    {
      return std::vector<double>(vector.begin(), vector.end());
    }

    // Sets the owned entries of `vector` from a checkpoint record.
    void
    set_owned_values(const io::CheckpointData &rank,
                     const std::string        &name,
                     VectorType               &vector)
    {
      const std::vector<double> &values =
        rank.get(name, static_cast<long long>(vector.locally_owned_size()));
      std::copy(values.begin(), values.end(), vector.begin());
      vector.compress(VectorOperation::insert);
    }
  } // namespace


  void
  TimeStepper::enable_checkpoints(const std::string        &directory,
                                  const double              interval,
                                  const io::CheckpointData &run_record)
  {
    checkpoint_directory = directory;
    checkpoint_interval  = interval;
    checkpoint_record    = run_record;
  }


  void
  TimeStepper::write_checkpoint()
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    io::CheckpointData run = checkpoint_record;
    io::CheckpointData rank;

    rank.set("u_n", owned_values(u_n));
    rank.set("v_n", owned_values(v_n));
    rank.set("u_nm1", owned_values(u_nm1));
    rank.set("v_nm1", owned_values(v_nm1));
    rank.set("last_increment", owned_values(last_increment));
    if (previous_forces.size() > 0)
      rank.set("prescribed_forces", owned_values(previous_forces));
    model.save_state(rank);

    run.set("step previous", previous_step);
    run.set("step last load increment", last_load_increment);
    run.set("control",
            {control.nominal,
             control.target,
             control.next,
             double(control.halvings),
             double(control.rejected),
             double(control.carried),
             control.span});
    run.set("loop",
            {loop.time,
             double(loop.step),
             loop.next_output,
             loop.next_checkpoint,
             double(loop.last_iterations),
             double(loop.failed_attempts)});
    run.set("summary",
            {double(summary.steps),
             double(summary.newton_iterations),
             double(summary.linear_iterations),
             double(summary.retries),
             double(summary.rejected),
             double(summary.tangents),
             summary.estimated_error});
    run.set("solver definite", newton.definite_factorization() ? 1. : 0.);
    save_core(run);
    output.save(run);

    io::write_checkpoint(checkpoint_directory, model.get_communicator(), run, rank);
    // Go on as the restart from this checkpoint does: a new tangent and AMG hierarchy.
    newton.renew();
    tangent_weights = {-1., -1.};
  }


  void
  TimeStepper::restore(const io::CheckpointData &run, const io::CheckpointData &rank)
  {
    set_owned_values(rank, "u_n", u_n);
    set_owned_values(rank, "v_n", v_n);
    set_owned_values(rank, "u_nm1", u_nm1);
    set_owned_values(rank, "v_nm1", v_nm1);
    set_owned_values(rank, "last_increment", last_increment);
    if (rank.has("prescribed_forces"))
      {
        model.initialize_owned(previous_forces);
        set_owned_values(rank, "prescribed_forces", previous_forces);
      }
    model.restore_state(rank);

    previous_step                = run.get_number("step previous");
    last_load_increment          = run.get_number("step last load increment");
    const std::vector<double> &c = run.get("control", 7);
    control.nominal              = c[0];
    control.target               = c[1];
    control.next                 = c[2];
    control.halvings             = static_cast<unsigned int>(c[3]);
    control.rejected             = static_cast<unsigned int>(c[4]);
    control.carried              = static_cast<unsigned int>(c[5]);
    control.span                 = c[6];
    const std::vector<double> &l = run.get("loop", 6);
    loop.time                    = l[0];
    loop.step                    = static_cast<unsigned int>(l[1]);
    loop.next_output             = l[2];
    loop.next_checkpoint         = l[3];
    loop.last_iterations         = static_cast<unsigned int>(l[4]);
    loop.failed_attempts         = static_cast<unsigned int>(l[5]);
    const std::vector<double> &t = run.get("summary", 7);
    summary.steps                = static_cast<unsigned int>(t[0]);
    summary.newton_iterations    = static_cast<unsigned int>(t[1]);
    summary.linear_iterations    = static_cast<unsigned int>(t[2]);
    summary.retries              = static_cast<unsigned int>(t[3]);
    summary.rejected             = static_cast<unsigned int>(t[4]);
    summary.tangents             = static_cast<unsigned int>(t[5]);
    summary.estimated_error      = t[6];
    newton.set_definite_factorization(run.get_number("solver definite") != 0.);
    restore_core(run);

    // A changed 'Checkpoint interval' takes effect from the next checkpoint time on.
    if (checkpoint_interval > 0. && loop.next_checkpoint <= loop.time)
      loop.next_checkpoint = loop.time + checkpoint_interval;
    model.import_ghosts(u_n, u_ghosted);
    model.import_ghosts(v_n, v_ghosted);
    resumed = true;
  }
} // namespace clothsim
