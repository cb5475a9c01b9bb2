#pragma once

// Everything a run writes into its output directory while it runs: solution.pvd with one
// solution-NNNNN.vtu (.pvtu plus one piece per rank under MPI) per output time,
// probes.csv and statistics.csv. Every frame and solution.pvd are written whole under a
// temporary name and renamed, CSV rows are appended whole (io/output_file.h), so a run
// that stops early, is killed, or fills the disk leaves a consistent record of everything
// up to that point. A failed write throws io::OutputError on every rank. The writer knows
// no model: it receives the mesh piece, the probes' dofs, the energy columns' names, and
// named fields per frame.

#include <deal.II/lac/trilinos_vector.h>

#include "io/checkpoint.h"
#include "io/output_file.h"
#include "io/probe_location.h"
#include "io/vtu_writer.h"

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace clothsim
{
  // One row of statistics.csv.
  struct StepStatistics
  {
    unsigned int        step;
    double              time; // s (load factor in static mode)
    double              dt;   // s
    unsigned int        newton_iterations;
    unsigned int        linear_iterations;
    double              residual;         // final Newton residual 2-norm, N
    unsigned int        retries;          // failed attempts (halvings) just before it
    double              kinetic_energy;   // J
    double              elastic_energy;   // J
    double              potential_energy; // J (total: their sum)
    std::vector<double> term_energies;    // J, one per extra energy column
    double              wall_seconds;     // since the run started
    unsigned int        rejected = 0;     // steps rejected by the error control before it
    double error_estimate        = 0.;    // local error estimate of the step, m (0: none)
    double assembly_seconds      = 0.;    // wall time of the step spent assembling
    double linear_solve_seconds  = 0.;    // ... in linear solves and preconditioners
  };

  // A support's reaction (reactions.csv): the force the group's pins exert on the cloth
  // and their moment about `centre`, the current centroid of the group's vertices,
  // including the moments the held rotations carry.
  struct SupportReaction
  {
    std::string  group;
    Point<3>     centre; // m
    Tensor<1, 3> force;  // N
    Tensor<1, 3> moment; // N·m
  };

  class OutputWriter
  {
  public:
    // `piece`: this rank's triangles for the VTK frames; `energy_columns`: the columns
    // of statistics.csv after the fixed ones (one per StepStatistics::term_energies).
    // With `resume` (a restart: the run's section of the checkpoint, see save()), the
    // directory's files continue from the checkpoint: the CSV files are cut back to
    // their rows at that time, later frames are removed, solution.pvd lists the frames
    // up to it.
    OutputWriter(const std::string                &directory,
                 const MPI_Comm                    communicator,
                 const io::SurfacePiece           &piece,
                 const std::vector<ProbeLocation> &probes,
                 const std::vector<std::string>   &energy_columns,
                 const bool                        write_vtk,
                 const io::CheckpointData         *resume = nullptr);

    // The output counters for a checkpoint (records "output ..."): the frames written
    // (times and file names) and the bytes of probes.csv and statistics.csv (rank 0's).
    void
    save(io::CheckpointData &run) const;

    // VTK frame (if enabled; `fields` is called for its data) and probe rows for the
    // displacement u (ghosted).
    void
    write_state(const unsigned int                    step,
                const double                          time,
                const TrilinosWrappers::MPI::Vector  &u,
                const std::function<io::FrameData()> &fields);

    void
    write_statistics(const StepStatistics &row);

    // Rows of reactions.csv (step,time,group,X,Y,Z,Fx,Fy,Fz,Mx,My,Mz) for the state
    // just written (the same on every rank; rank 0 writes). The file is made with the
    // first call: a run without pinned or clamped groups has none.
    void
    write_reactions(const unsigned int                  step,
                    const double                        time,
                    const std::vector<SupportReaction> &reactions);

    const std::string &
    get_directory() const
    {
      return directory;
    }

    // Called with every written state (time, ghosted displacement), e.g. to compare runs.
    using FrameObserver =
      std::function<void(const double time, const TrilinosWrappers::MPI::Vector &u)>;
    void
    set_frame_observer(const FrameObserver &observer)
    {
      frame_observer = observer;
    }

    // solution.pvd gives each frame its step number as its time instead of the state's
    // time (an arc-length path's load factor, which can fall: ParaView orders frames by
    // that value). The CSV files and the frames' own time field keep the state's.
    void
    number_frames_by_step()
    {
      frames_by_step = true;
    }

    // The run's closing summary, for its log: each probe's displacement in the last
    // written state, the energies of the first and last statistics rows, the work
    // dissipated (columns named *_dissipated), the energy given from outside (columns
    // prescribed_work, strain_limit_energy, stiffness_raise_energy), with the balance
    // total + dissipated - given,
    // and the path of solution.pvd to open in ParaView.
    void
    print_summary(std::ostream &out) const;

    // The balance of print_summary(), total + dissipated - given from the first
    // statistics row to the last (J; 0 before any row), and the energy the run had
    // to move with: the first row's K + W plus the largest |P| of any row written plus
    // the largest |energy given from outside| (prescribed work, strain limit, stiffness
    // raises, each from the first row) of any row written (J).
    double
    energy_balance_change() const;
    double
    energy_scale() const;

  private:
    // The restart's part of the constructor (see there).
    void
    continue_from(const io::CheckpointData &resume);

    const std::string                           directory;
    const MPI_Comm                              communicator;
    const io::SurfacePiece                      piece;
    const std::vector<ProbeLocation>            probes;
    const std::vector<std::string>              energy_columns;
    const bool                                  write_vtk;
    const bool                                  is_root;
    io::RowFile                                 probes_csv;
    io::RowFile                                 statistics_csv;
    io::RowFile                                 reactions_csv; // opened on first use
    bool                                        reactions_open = false;
    std::vector<std::pair<double, std::string>> frames;
    bool                                        frames_by_step = false;
    FrameObserver                               frame_observer;
    // For print_summary(): the last state's time and probe values (3 per probe), the
    // first and last statistics rows.
    double                        last_state_time = 0.;
    std::vector<double>           last_probe_values;
    std::optional<StepStatistics> first_statistics, last_statistics;
    double                        largest_potential = 0.; // J, of any row
    double                        largest_added     = 0.; // J, of any row
  };
} // namespace clothsim
