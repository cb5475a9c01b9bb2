#include "io/output_writer.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>

namespace clothsim
{
  OutputWriter::OutputWriter(const std::string                &directory,
                             const ClothModel                 &model,
                             const std::vector<ProbeLocation> &probes,
                             const bool                        write_vtk)
    : directory(directory)
    , model(model)
    , probes(probes)
    , write_vtk(write_vtk)
    , is_root(Utilities::MPI::this_mpi_process(model.get_communicator()) == 0)
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
             "linear_solve_seconds\n"
          << std::flush;
      }
  }


  void
  OutputWriter::write_state(const unsigned int step,
                            const double       time,
                            const VectorType  &u,
                            const VectorType  &v)
  {
    if (write_vtk)
      write_vtk_frame(time, u, v);
    if (frame_observer)
      frame_observer(time, u);

    std::vector<types::global_dof_index> dofs;
    for (const ProbeLocation &probe : probes)
      dofs.insert(dofs.end(), probe.dofs.begin(), probe.dofs.end());
    const std::vector<double> values = model.gather_values(u, dofs);
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
    if (!is_root)
      return;
    const Energies &e = row.energies;
    statistics_csv << std::setprecision(12) << row.step << ',' << row.time << ','
                   << row.dt << ',' << row.newton_iterations << ','
                   << row.linear_iterations << ',' << row.residual << ',' << row.retries
                   << ',' << e.kinetic << ',' << e.elastic << ',' << e.potential << ','
                   << e.kinetic + e.elastic + e.potential << ',' << std::setprecision(4)
                   << row.wall_seconds << ',' << row.rejected << ','
                   << std::setprecision(6) << row.error_estimate << ','
                   << std::setprecision(4) << row.assembly_seconds << ','
                   << row.linear_solve_seconds << '\n'
                   << std::flush;
  }


  void
  OutputWriter::write_vtk_frame(const double      time,
                                const VectorType &u,
                                const VectorType &v)
  {
    const MPI_Comm     communicator = model.get_communicator();
    const unsigned int n_ranks      = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank         = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int frame        = frames.size();

    DataOut<2, 3> data_out;
    data_out.attach_dof_handler(model.get_dof_handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
      3, DataComponentInterpretation::component_is_part_of_vector);
    if (model.has_bending())
      vector_field.push_back(DataComponentInterpretation::component_is_scalar);
    data_out.add_data_vector(u,
                             model.component_names("displacement"),
                             DataOut<2, 3>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(v,
                             model.component_names("velocity"),
                             DataOut<2, 3>::type_dof_data,
                             vector_field);
    Vector<double> strain, stress, edge_strain;
    model.cell_strain_stress(u, strain, stress);
    data_out.add_data_vector(strain, "green_strain", DataOut<2, 3>::type_cell_data);
    if (model.uses_springs())
      {
        // The springs' stress is not the continuum's: show their strain instead.
        model.cell_edge_strain(u, edge_strain);
        data_out.add_data_vector(edge_strain,
                                 "spring_strain",
                                 DataOut<2, 3>::type_cell_data);
      }
    else
      data_out.add_data_vector(stress, "membrane_stress", DataOut<2, 3>::type_cell_data);
    Vector<double> curvature;
    if (model.has_bending())
      {
        model.cell_curvature_change(u, curvature);
        data_out.add_data_vector(curvature,
                                 "curvature_change",
                                 DataOut<2, 3>::type_cell_data);
      }
    Vector<float> subdomain(model.get_dof_handler().get_triangulation().n_active_cells());
    subdomain = static_cast<float>(rank);
    data_out.add_data_vector(subdomain, "rank", DataOut<2, 3>::type_cell_data);
    data_out.build_patches(model.get_mapping(), 1);

    DataOutBase::VtkFlags flags;
    flags.time              = time;
    flags.cycle             = frame;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);

    const std::string stem = "solution-" + Utilities::int_to_string(frame, 5);
    std::string       record;
    if (n_ranks == 1)
      {
        record = stem + ".vtu";
        std::ofstream out(directory + "/" + record);
        data_out.write_vtu(out);
      }
    else
      {
        const std::string piece = stem + "." + Utilities::int_to_string(rank, 4) + ".vtu";
        {
          std::ofstream out(directory + "/" + piece);
          data_out.write_vtu(out);
        }
        record = stem + ".pvtu";
        if (rank == 0)
          {
            std::vector<std::string> pieces;
            for (unsigned int r = 0; r < n_ranks; ++r)
              pieces.push_back(stem + "." + Utilities::int_to_string(r, 4) + ".vtu");
            std::ofstream out(directory + "/" + record);
            data_out.write_pvtu_record(out, pieces);
          }
      }
    frames.emplace_back(time, record);

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
} // namespace clothsim
