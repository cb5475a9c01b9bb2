#include "io/output_writer.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <filesystem>
#include <iomanip>

namespace clothsim
{
  OutputWriter::OutputWriter(const std::string                &directory,
                             const MPI_Comm                    communicator,
                             const io::SurfacePiece           &piece,
                             const std::vector<ProbeLocation> &probes,
                             const std::vector<std::string>   &energy_columns,
                             const bool                        write_vtk)
    : directory(directory)
    , communicator(communicator)
    , piece(piece)
    , probes(probes)
    , n_energy_columns(energy_columns.size())
    , write_vtk(write_vtk)
    , is_root(Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    if (is_root)
      {
        probes_csv.open(directory + "/probes.csv");
        probes_csv << "step,time,probe,X,Y,Z,ux,uy,uz\n" << std::flush;
        statistics_csv.open(directory + "/statistics.csv");
        statistics_csv
          << "step,time,dt,newton_iterations,linear_iterations,residual,retries,"
             "kinetic_energy,elastic_energy,potential_energy,total_energy,"
             "wall_seconds,rejected,error_estimate,assembly_seconds,"
             "linear_solve_seconds";
        for (const std::string &column : energy_columns)
          statistics_csv << ',' << column;
        statistics_csv << '\n' << std::flush;
      }
  }


  void
  OutputWriter::write_state(const unsigned int                    step,
                            const double                          time,
                            const TrilinosWrappers::MPI::Vector  &u,
                            const std::function<io::FrameData()> &fields)
  {
    if (write_vtk)
      {
        const std::string stem = "solution-" + Utilities::int_to_string(frames.size(), 5);
        frames.emplace_back(
          time,
          io::write_vtu_frame(directory, stem, piece, fields(), time, communicator));
        // Replace solution.pvd atomically, so that it always lists complete frames only.
        MPI_Barrier(communicator);
        if (is_root)
          {
            const std::string pvd = directory + "/solution.pvd";
            {
              std::ofstream out(pvd + ".tmp");
              DataOutBase::write_pvd_record(out, frames);
            }
            std::filesystem::rename(pvd + ".tmp", pvd);
          }
      }
    if (frame_observer)
      frame_observer(time, u);

    // Probe values: each from the rank that owns it.
    std::vector<double> values(3 * probes.size(), 0.);
    for (unsigned int p = 0; p < probes.size(); ++p)
      for (unsigned int d = 0; d < 3; ++d)
        if (u.locally_owned_elements().is_element(probes[p].dofs[d]))
          values[3 * p + d] = u(probes[p].dofs[d]);
    MPI_Allreduce(
      MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM, communicator);
    if (is_root)
      {
        probes_csv << std::setprecision(12);
        for (unsigned int p = 0; p < probes.size(); ++p)
          {
            const Point<3> &X = probes[p].reference_point;
            probes_csv << step << ',' << time << ',' << probes[p].name << ',' << X[0]
                       << ',' << X[1] << ',' << X[2] << ',' << values[3 * p] << ','
                       << values[3 * p + 1] << ',' << values[3 * p + 2] << '\n';
          }
        probes_csv << std::flush;
      }
  }


  void
  OutputWriter::write_statistics(const StepStatistics &row)
  {
    AssertDimension(row.term_energies.size(), n_energy_columns);
    if (!is_root)
      return;
    statistics_csv << std::setprecision(12) << row.step << ',' << row.time << ','
                   << row.dt << ',' << row.newton_iterations << ','
                   << row.linear_iterations << ',' << row.residual << ',' << row.retries
                   << ',' << row.kinetic_energy << ',' << row.elastic_energy << ','
                   << row.potential_energy << ','
                   << row.kinetic_energy + row.elastic_energy + row.potential_energy
                   << ',' << std::setprecision(4) << row.wall_seconds << ','
                   << row.rejected << ',' << std::setprecision(6) << row.error_estimate
                   << ',' << std::setprecision(4) << row.assembly_seconds << ','
                   << row.linear_solve_seconds << std::setprecision(12);
    for (const double energy : row.term_energies)
      statistics_csv << ',' << energy;
    statistics_csv << '\n' << std::flush;
  }
} // namespace clothsim
