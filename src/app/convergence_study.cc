#include "app/convergence_study.h"

#include <deal.II/base/convergence_table.h>
#include <deal.II/grid/tria.h>

#include "app/study_run.h"
#include "io/collective.h"
#include "io/input_error.h"
#include "io/line_plot.h"
#include "io/output_file.h"
#include "mesh/memory_estimate.h"
#include "scene/scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace clothsim
{
  namespace
  {
    using Vertices = std::vector<std::array<double, 6>>;

    // One error column of a study: a quantity and what it is measured against.
    struct Quantity
    {
      std::string         name;      // probe:<name>, mesh_max, mesh_rms
      std::string         reference; // closed form, richardson, finest run
      std::vector<double> errors;    // per run; NaN where not defined
    };

    // The runs of one study (space or time) and their errors.
    struct Study
    {
      std::string           name; // "space", "time"
      std::vector<StudyRun> runs;
      std::vector<double>   sizes; // mesh size relative to the coarsest, or dt (s)
      std::vector<Quantity> quantities;
    };

    // u_K + (u_K - u_K-1) / (2^p - 1), on the vertices of `coarsest`.
    Vertices
    extrapolate(const Vertices &finest, const Vertices &second, const double p)
    {
      Vertices result = finest;
      for (unsigned int i = 0; i < result.size(); ++i)
        for (unsigned int d = 3; d < 6; ++d)
          result[i][d] += (finest[i][d] - second[i][d]) / (std::pow(2., p) - 1.);
      return result;
    }

    // Computes the study's errors (rank 0: the vertices live there).
    void
    evaluate_errors(Study &study, const bool closed_form_allowed)
    {
      std::vector<unsigned int> done;
      for (unsigned int i = 0; i < study.runs.size(); ++i)
        if (study.runs[i].completed)
          done.push_back(i);
      const unsigned int n = study.runs.size();
      if (done.size() < 2)
        return;
      const Vertices &coarsest = study.runs[done.front()].vertices;
      // Every run on the coarsest run's vertices.
      std::vector<Vertices> on_coarse(n);
      for (const unsigned int i : done)
        on_coarse[i] = restrict_to(study.runs[i].vertices, coarsest);

      // Reference: Richardson from the three finest completed runs (each quantity its
      // own observed order p), or the finest run.
      const unsigned int k     = done.back();
      const bool         three = done.size() >= 3;
      const unsigned int j     = three ? done[done.size() - 2] : k,
                         i     = three ? done[done.size() - 3] : k;
      const auto order         = [three](const double d1, const double d2) {
        const double p = three && d2 > 0. ? std::log2(d1 / d2) : 0.;
        return p >= 0.5 && p <= 8. ? p : 0.;
      };
      const auto name_of = [](const double p) {
        std::ostringstream name;
        if (p > 0.)
          name << "richardson (p = " << std::setprecision(3) << p << ")";
        else
          name << "finest run";
        return name.str();
      };

      const std::vector<Probe> &probes = study.runs[k].probes;
      for (unsigned int q = 0; q < probes.size(); ++q)
        {
          const auto &P = [&](const unsigned int r) {
            return study.runs[r].probe_displacements[q];
          };
          const double p = order((P(i) - P(j)).norm(), (P(j) - P(k)).norm());
          Quantity     quantity{"probe:" + probes[q].name, name_of(p), {}};
          Tensor<1, 3> target = P(k);
          if (p > 0.)
            target += (P(k) - P(j)) / (std::pow(2., p) - 1.);
          const bool closed = closed_form_allowed && probes[q].has_reference;
          if (closed)
            {
              target             = probes[q].reference_displacement;
              quantity.reference = "closed form";
            }
          for (unsigned int r = 0; r < n; ++r)
            quantity.errors.push_back(study.runs[r].completed &&
                                          (closed || p > 0. || r != k)
                                        ? (P(r) - target).norm()
                                        : std::numeric_limits<double>::quiet_NaN());
          study.quantities.push_back(quantity);
        }

      const double   p = order(field_difference(on_coarse[i], on_coarse[j]).largest,
                             field_difference(on_coarse[j], on_coarse[k]).largest);
      const Vertices reference =
        p > 0. ? extrapolate(on_coarse[k], on_coarse[j], p) : on_coarse[k];
      const std::string reference_name = name_of(p);
      const bool        with_finest    = p > 0.;
      Quantity          largest{"mesh_max", reference_name, {}},
        rms{"mesh_rms", reference_name, {}};
      for (unsigned int i = 0; i < n; ++i)
        {
          double e_max = std::numeric_limits<double>::quiet_NaN(), e_rms = e_max;
          if (study.runs[i].completed && (with_finest || i != k))
            {
              const FieldDifference difference =
                field_difference(on_coarse[i], reference);
              e_max = difference.largest;
              e_rms = difference.rms;
            }
          largest.errors.push_back(e_max);
          rms.errors.push_back(e_rms);
        }
      study.quantities.push_back(largest);
      study.quantities.push_back(rms);
    }

    double
    observed_order(const std::vector<double> &errors, const unsigned int i)
    {
      if (i == 0 || !(errors[i - 1] > 0.) || !(errors[i] > 0.))
        return std::numeric_limits<double>::quiet_NaN();
      return std::log2(errors[i - 1] / errors[i]);
    }

    void
    print_table(const Study &study, std::ostream &out)
    {
      ConvergenceTable table;
      for (unsigned int i = 0; i < study.runs.size(); ++i)
        {
          bool any = false;
          for (const Quantity &quantity : study.quantities)
            any = any || std::isfinite(quantity.errors[i]);
          if (!any)
            continue;
          table.add_value("level", i);
          table.add_value(study.name == "space" ? "h/h0" : "dt", study.sizes[i]);
          table.add_value("unknowns", static_cast<unsigned int>(study.runs[i].unknowns));
          for (const Quantity &quantity : study.quantities)
            table.add_value(quantity.name, quantity.errors[i]);
        }
      table.set_scientific(study.name == "space" ? "h/h0" : "dt", true);
      for (const Quantity &quantity : study.quantities)
        {
          table.set_scientific(quantity.name, true);
          table.set_precision(quantity.name, 3);
          table.evaluate_convergence_rates(quantity.name,
                                           ConvergenceTable::reduction_rate_log2);
        }
      out << study.name << " convergence (errors in m; reference: ";
      for (const Quantity &quantity : study.quantities)
        out << quantity.name << " " << quantity.reference
            << (&quantity == &study.quantities.back() ? ")\n" : ", ");
      table.write_text(out, TableHandler::org_mode_table);
    }

    void
    write_csv(const std::vector<Study> &studies, const std::string &file)
    {
      io::write_file_atomically(file, [&](std::ostream &csv) {
        csv << "study,level,size,unknowns,quantity,reference,error,observed_order\n"
            << std::setprecision(10);
        for (const Study &study : studies)
          for (const Quantity &quantity : study.quantities)
            for (unsigned int i = 0; i < study.runs.size(); ++i)
              {
                if (!std::isfinite(quantity.errors[i]))
                  continue;
                const double order = observed_order(quantity.errors, i);
                csv << study.name << ',' << i << ',' << study.sizes[i] << ','
                    << study.runs[i].unknowns << ',' << quantity.name << ",\""
                    << quantity.reference << "\"," << quantity.errors[i] << ',';
                if (std::isfinite(order))
                  csv << order;
                csv << '\n';
              }
      });
    }

    // Returns whether gnuplot drew it (io/line_plot.h).
    bool
    write_plot(const std::vector<Study> &studies, const std::string &file)
    {
      static const std::array<std::array<unsigned char, 3>, 6> colors = {
        {{{31, 119, 180}},
         {{214, 39, 40}},
         {{44, 160, 44}},
         {{148, 103, 189}},
         {{255, 127, 14}},
         {{23, 190, 207}}}};
      std::vector<io::PlotPanel> panels;
      for (const Study &study : studies)
        {
          io::PlotPanel panel;
          panel.title   = study.name + " convergence: error at the end against the "
                                       "reference";
          panel.x_label = study.name == "space" ? "mesh size h/h0" : "time step dt (s)";
          panel.y_label = "error (m)";
          panel.log_x   = true;
          panel.log_y   = true;
          // First order (backward Euler) and second (P1 membrane and shell, BDF2, the
          // midpoint rule): the orders the methods can reach.
          panel.reference_orders = {1., 2.};
          for (unsigned int q = 0; q < study.quantities.size(); ++q)
            {
              io::PlotSeries series;
              series.label   = study.quantities[q].name;
              series.x       = study.sizes;
              series.y       = study.quantities[q].errors;
              series.color   = colors[q % colors.size()];
              series.markers = true;
              series.dashed  = study.quantities[q].name == "mesh_rms";
              panel.series.push_back(series);
            }
          panels.push_back(panel);
        }
      return !panels.empty() && io::write_line_plot(file, panels);
    }
  } // namespace


  int
  run_convergence_study(const CommandLine  &command_line,
                        const std::string  &file,
                        const std::string  &directory,
                        const MPI_Comm      communicator,
                        ConditionalOStream &pcout)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    // All input is read and checked before anything is written.
    const std::unique_ptr<Scene> base =
      load_scene(file, command_line.overrides, communicator);
    const Parameters  &parameters = base->parameters();
    const unsigned int base_level = parameters.scene.global_refinements;
    const double       base_step  = parameters.time.time_step;
    const bool         dynamic    = !is_static(parameters.time.integrator);
    if (command_line.time_levels > 0 && !dynamic)
      throw InputError(file,
                       "--time",
                       "a static run has no time step to halve (its load steps do not "
                       "change the equilibrium); use --space");
    if (command_line.time_levels > 0 && parameters.time.adaptive_time_steps)
      throw InputError(file,
                       "--time",
                       "the steps are adaptive; halve 'Time/Error tolerance' instead, or "
                       "turn 'Adaptive time steps' off");

    // The finest mesh must be allowed and fit in memory: found out now, not after the
    // coarser runs have written their output.
    if (command_line.space_levels > 0)
      {
        mesh::MeshSetup finest;
        finest.global_refinements = base_level + command_line.space_levels;
        finest.directors          = base->model->get_discretization().has_directors();
        if (finest.global_refinements > 8)
          throw InputError(file,
                           "--space",
                           "'Mesh/Global refinements' + K is " +
                             std::to_string(finest.global_refinements) +
                             ", beyond its largest value 8");
        const mesh::MemoryEstimate estimate =
          mesh::estimate_memory(communicator,
                                base->serial_mesh->n_active_cells(),
                                finest);
        if (!estimate.fits())
          throw InputError(file, "--space", estimate.shortage());
      }

    std::vector<Study> studies;
    bool               all_completed = true;
    for (const std::string name : {"space", "time"})
      {
        const unsigned int levels =
          name == "space" ? command_line.space_levels : command_line.time_levels;
        if (levels == 0)
          continue;
        Study study;
        study.name = name;
        for (unsigned int i = 0; i <= levels; ++i)
          {
            std::vector<std::string> overrides = command_line.overrides;
            const double             size =
              name == "space" ? std::pow(0.5, i) : base_step * std::pow(0.5, i);
            const std::string level_setting =
              name == "space"
                ? "Mesh/Global refinements=" + std::to_string(base_level + i)
                : "Time/Time step=" + parameter_value(size);
            overrides.push_back(level_setting);
            const std::string run_directory =
              directory + "/" + name + "-" + std::to_string(i);
            pcout << name << " level " << i << " (" << level_setting << ") ..."
                  << std::flush;
            StudyRun run = run_study_case(file, overrides, run_directory, communicator);
            pcout << (run.completed ? " done" : " FAILED: " + run.failure) << " in "
                  << run.wall_seconds << " s, " << run.unknowns << " unknowns, "
                  << run.summary.steps << " steps" << std::endl;
            all_completed = all_completed && run.completed;
            study.sizes.push_back(size);
            study.runs.push_back(std::move(run));
          }
        if (is_root)
          evaluate_errors(study, name == "space");
        studies.push_back(std::move(study));
      }

    io::run_collectively(communicator, [&]() {
      if (is_root)
        {
          for (const Study &study : studies)
            {
              if (study.quantities.empty())
                std::cout << study.name
                          << " convergence: fewer than two runs completed, no errors\n";
              else
                print_table(study, std::cout);
            }
          write_csv(studies, directory + "/convergence.csv");
          const bool plotted = write_plot(studies, directory + "/convergence.png");
          std::cout << "wrote " << directory << "/convergence.csv"
                    << (plotted ? " and convergence.png, .svg" : "") << std::endl;
        }
    });
    return all_completed ? 0 : 2;
  }
} // namespace clothsim
