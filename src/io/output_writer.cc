#include "io/output_writer.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "io/collective.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <regex>
#include <sstream>

namespace clothsim
{
  namespace
  {
    // The work a dissipative term has taken out of the motion: its column ends so.
    bool
    is_dissipated_column(const std::string &name)
    {
      const std::string suffix = "_dissipated";
      return name.size() > suffix.size() &&
             name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    }

    // Energy given to the cloth from outside its equations: the work of prescribed
    // motion, the strain limit's corrections, raises of the barrier stiffness.
    bool
    is_added_column(const std::string &name)
    {
      return name == "prescribed_work" || name == "strain_limit_energy" ||
             name == "stiffness_raise_energy";
    }
  } // namespace


  OutputWriter::OutputWriter(const std::string                &directory,
                             const MPI_Comm                    communicator,
                             const io::SurfacePiece           &piece,
                             const std::vector<ProbeLocation> &probes,
                             const std::vector<std::string>   &energy_columns,
                             const bool                        write_vtk,
                             const io::CheckpointData         *resume)
    : directory(directory)
    , communicator(communicator)
    , piece(piece)
    , probes(probes)
    , energy_columns(energy_columns)
    , write_vtk(write_vtk)
    , is_root(Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    if (resume != nullptr)
      {
        continue_from(*resume);
        return;
      }
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      probes_csv.open(directory + "/probes.csv");
      probes_csv.append("step,time,probe,X,Y,Z,ux,uy,uz\n");
      statistics_csv.open(directory + "/statistics.csv");
      std::string header = "step,time,dt,newton_iterations,linear_iterations,residual,"
                           "retries,kinetic_energy,elastic_energy,potential_energy,"
                           "total_energy,wall_seconds,rejected,error_estimate,"
                           "assembly_seconds,linear_solve_seconds";
      for (const std::string &column : energy_columns)
        header += ',' + column;
      statistics_csv.append(header + '\n');
    });
  }


  void
  OutputWriter::save(io::CheckpointData &run) const
  {
    std::vector<double> times;
    std::string         names;
    for (const auto &[time, name] : frames)
      {
        times.push_back(time);
        names += name + '\n';
      }
    run.set("output frame times", times);
    run.set_text("output frame files", names);
    run.set("output probes.csv bytes", static_cast<double>(probes_csv.size()));
    run.set("output statistics.csv bytes", static_cast<double>(statistics_csv.size()));
    run.set("output reactions.csv bytes",
            reactions_open ? static_cast<double>(reactions_csv.size()) : 0.);
  }


  void
  OutputWriter::continue_from(const io::CheckpointData &resume)
  {
    const std::vector<double> &times = resume.get("output frame times");
    std::istringstream         names(resume.get_text("output frame files"));
    frames.clear();
    for (const double time : times)
      {
        std::string name;
        std::getline(names, name);
        frames.emplace_back(time, name);
      }
    const long long probe_bytes      = resume.get_number("output probes.csv bytes");
    const long long statistics_bytes = resume.get_number("output statistics.csv bytes");
    const long long reactions_bytes  = resume.get_number("output reactions.csv bytes");
    reactions_open                   = reactions_bytes > 0;
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      probes_csv.reopen_at(directory + "/probes.csv", probe_bytes);
      statistics_csv.reopen_at(directory + "/statistics.csv", statistics_bytes);
      if (reactions_open)
        reactions_csv.reopen_at(directory + "/reactions.csv", reactions_bytes);
      // Frames written after the checkpoint (their pieces and records) go; the new ones
      // take their numbers.
      namespace fs = std::filesystem;
      const std::regex frame_file(
        "solution-([0-9]{5})([.][0-9]{4})?[.](vtu|pvtu)([.]partial)?");
      std::error_code error;
      for (fs::directory_iterator entry(directory, error), end; !error && entry != end;
           entry.increment(error))
        {
          std::smatch       match;
          const std::string name = entry->path().filename().string();
          if (std::regex_match(name, match, frame_file) &&
              std::stoul(match[1].str()) >= frames.size())
            fs::remove(entry->path(), error);
        }
      if (error)
        throw io::OutputError(directory,
                              "cannot remove the frames written after the checkpoint: " +
                                error.message());
      if (write_vtk)
        io::write_file_atomically(directory + "/solution.pvd", [this](std::ostream &out) {
          DataOutBase::write_pvd_record(out, frames);
        });
    });
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
          frames_by_step ? static_cast<double>(step) : time,
          io::write_vtu_frame(directory, stem, piece, fields(), time, communicator));
      }
    if (frame_observer)
      frame_observer(time, u);

    // Probe values, interpolated in their triangles.
    std::vector<double> values;
    for (const Tensor<1, 3> &displacement : probe_displacements(probes, u, communicator))
      values.insert(values.end(), displacement.begin_raw(), displacement.end_raw());
    last_state_time   = time;
    last_probe_values = values;
    // solution.pvd lists complete frames only; then the probes' rows.
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      if (write_vtk)
        io::write_file_atomically(directory + "/solution.pvd", [this](std::ostream &out) {
          DataOutBase::write_pvd_record(out, frames);
        });
      std::ostringstream rows;
      rows << std::setprecision(12);
      for (unsigned int p = 0; p < probes.size(); ++p)
        {
          const Point<3> &X = probes[p].reference_point;
          rows << step << ',' << time << ',' << probes[p].name << ',' << X[0] << ','
               << X[1] << ',' << X[2] << ',' << values[3 * p] << ',' << values[3 * p + 1]
               << ',' << values[3 * p + 2] << '\n';
        }
      probes_csv.append(rows.str());
    });
  }


  void
  OutputWriter::write_statistics(const StepStatistics &row)
  {
    AssertDimension(row.term_energies.size(), energy_columns.size());
    if (!first_statistics)
      first_statistics = row;
    last_statistics   = row;
    largest_potential = std::max(largest_potential, std::abs(row.potential_energy));
    double added      = 0.;
    for (unsigned int c = 0; c < energy_columns.size(); ++c)
      if (is_added_column(energy_columns[c]))
        added += std::abs(row.term_energies[c] - first_statistics->term_energies[c]);
    largest_added = std::max(largest_added, added);
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      std::ostringstream line;
      line << std::setprecision(12) << row.step << ',' << row.time << ',' << row.dt << ','
           << row.newton_iterations << ',' << row.linear_iterations << ',' << row.residual
           << ',' << row.retries << ',' << row.kinetic_energy << ',' << row.elastic_energy
           << ',' << row.potential_energy << ','
           << row.kinetic_energy + row.elastic_energy + row.potential_energy << ','
           << std::setprecision(4) << row.wall_seconds << ',' << row.rejected << ','
           << std::setprecision(6) << row.error_estimate << ',' << std::setprecision(4)
           << row.assembly_seconds << ',' << row.linear_solve_seconds
           << std::setprecision(12);
      for (const double energy : row.term_energies)
        line << ',' << energy;
      line << '\n';
      statistics_csv.append(line.str());
    });
  }


  void
  OutputWriter::write_reactions(const unsigned int                  step,
                                const double                        time,
                                const std::vector<SupportReaction> &reactions)
  {
    io::run_collectively(communicator, [&]() {
      if (!is_root)
        return;
      if (!reactions_open)
        {
          reactions_csv.open(directory + "/reactions.csv");
          reactions_csv.append("step,time,group,X,Y,Z,Fx,Fy,Fz,Mx,My,Mz\n");
          reactions_open = true;
        }
      std::ostringstream rows;
      rows << std::setprecision(12);
      for (const SupportReaction &reaction : reactions)
        {
          rows << step << ',' << time << ',' << reaction.group;
          for (const double value : {reaction.centre[0],
                                     reaction.centre[1],
                                     reaction.centre[2],
                                     reaction.force[0],
                                     reaction.force[1],
                                     reaction.force[2],
                                     reaction.moment[0],
                                     reaction.moment[1],
                                     reaction.moment[2]})
            rows << ',' << value;
          rows << '\n';
        }
      reactions_csv.append(rows.str());
    });
  }


  double
  OutputWriter::energy_balance_change() const
  {
    if (!first_statistics || !last_statistics)
      return 0.;
    const StepStatistics &first = *first_statistics, &last = *last_statistics;
    double                change =
      last.kinetic_energy + last.elastic_energy + last.potential_energy -
      (first.kinetic_energy + first.elastic_energy + first.potential_energy);
    for (unsigned int c = 0; c < energy_columns.size(); ++c)
      if (is_dissipated_column(energy_columns[c]))
        change += last.term_energies[c] - first.term_energies[c];
      else if (is_added_column(energy_columns[c]))
        change -= last.term_energies[c] - first.term_energies[c];
    return change;
  }


  double
  OutputWriter::energy_scale() const
  {
    if (!first_statistics)
      return 0.;
    return first_statistics->kinetic_energy + first_statistics->elastic_energy +
           largest_potential + largest_added;
  }


  void
  OutputWriter::print_summary(std::ostream &out) const
  {
    if (!probes.empty() && !last_probe_values.empty())
      {
        out << "  probes at t = " << last_state_time << " s, displacement (m):";
        for (unsigned int p = 0; p < probes.size(); ++p)
          {
            const double *u = &last_probe_values[3 * p];
            out << (p == 0 ? " " : "; ") << probes[p].name << " (" << u[0] << ", " << u[1]
                << ", " << u[2] << "), |u| " << std::hypot(u[0], u[1], u[2]);
          }
        out << "\n";
      }
    if (first_statistics && last_statistics)
      {
        const auto total = [](const StepStatistics &row) {
          return row.kinetic_energy + row.elastic_energy + row.potential_energy;
        };
        const StepStatistics &first = *first_statistics, &last = *last_statistics;
        out << "  energy (J) from t = " << first.time << " to " << last.time
            << " s: kinetic " << first.kinetic_energy << " -> " << last.kinetic_energy
            << ", elastic " << first.elastic_energy << " -> " << last.elastic_energy
            << ", potential " << first.potential_energy << " -> " << last.potential_energy
            << ", total " << total(first) << " -> " << total(last);
        std::string added;
        for (unsigned int c = 0; c < energy_columns.size(); ++c)
          if (is_dissipated_column(energy_columns[c]) ||
              is_added_column(energy_columns[c]))
            {
              out << "; " << energy_columns[c] << " " << last.term_energies[c];
              if (is_added_column(energy_columns[c]))
                added += " - " + energy_columns[c];
            }
        out << "; total + dissipated" << added << " changed by "
            << energy_balance_change() << "\n";
      }
    if (write_vtk)
      {
        std::error_code error;
        const auto path = std::filesystem::absolute(directory + "/solution.pvd", error)
                            .lexically_normal();
        out << "  open in ParaView: "
            << (error ? directory + "/solution.pvd" : path.string()) << "\n";
      }
    else
      out << "  results: " << directory << " (probes.csv, statistics.csv; no frames: "
          << "Output/Write VTK = false)\n";
  }
} // namespace clothsim
