#include "app/speed_accuracy_sweep.h"

#include <deal.II/base/utilities.h>

#include "app/study_run.h"
#include "io/collective.h"
#include "io/input_error.h"
#include "io/line_plot.h"
#include "io/output_file.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace clothsim
{
  namespace
  {
    std::string
    joined(const std::vector<std::string> &assignments)
    {
      std::string text;
      for (const std::string &assignment : assignments)
        text += (text.empty() ? "" : " & ") + assignment;
      return text;
    }

    // The value an assignment list gives to `entry`, or "".
    std::string
    value_of(const std::vector<std::string> &assignments, const std::string &entry)
    {
      std::string value;
      for (const std::string &assignment : assignments)
        if (assignment.rfind(entry + "=", 0) == 0)
          value = Utilities::trim(assignment.substr(entry.size() + 1));
      return value;
    }

    struct SweepPoint
    {
      std::vector<std::string> setting;
      StudyRun                 run;
      std::string              status; // completed, failed, invalid input
      double                   error     = std::numeric_limits<double>::infinity();
      double                   rms_error = std::numeric_limits<double>::infinity();
      bool                     on_front  = false;
    };

    // Marks the points no other completed point beats in both runtime and error.
    void
    mark_front(std::vector<SweepPoint> &points)
    {
      std::vector<SweepPoint *> completed;
      for (SweepPoint &point : points)
        if (point.status == "completed")
          completed.push_back(&point);
      std::sort(completed.begin(), completed.end(), [](const auto *a, const auto *b) {
        return a->run.wall_seconds < b->run.wall_seconds ||
               (a->run.wall_seconds == b->run.wall_seconds && a->error < b->error);
      });
      double best = std::numeric_limits<double>::infinity();
      for (SweepPoint *point : completed)
        if (point->error < best)
          {
            point->on_front = true;
            best            = point->error;
          }
    }

    void
    write_csv(const std::vector<SweepPoint> &points,
              const SweepPoint              &reference,
              const std::string             &file)
    {
      io::write_file_atomically(file, [&](std::ostream &csv) {
        csv << "setting,runtime_seconds,error,rms_error,steps,newton_iterations,status,"
               "on_front\n"
            << std::setprecision(8);
        const auto row = [&csv](const SweepPoint &point, const std::string &setting) {
          csv << '"' << setting << "\"," << point.run.wall_seconds << ',' << point.error
              << ',' << point.rms_error << ',' << point.run.summary.steps << ','
              << point.run.summary.newton_iterations << ',' << point.status << ','
              << (point.on_front ? "true" : "false") << '\n';
        };
        for (const SweepPoint &point : points)
          row(point, joined(point.setting));
        row(reference, "reference: " + joined(reference.setting));
      });
    }

    // Returns whether gnuplot drew it (io/line_plot.h).
    bool
    write_plot(const std::vector<SweepPoint> &points, const std::string &file)
    {
      io::PlotPanel panel;
      panel.title   = "speed against accuracy (Pareto front joined)";
      panel.x_label = "runtime (s)";
      panel.y_label = "error at the end (m)";
      panel.log_x   = true;
      panel.log_y   = true;
      io::PlotSeries fem{"fem", {}, {}, {{31, 119, 180}}};
      io::PlotSeries springs{"mass-spring", {}, {}, {{255, 127, 14}}};
      io::PlotSeries front{"Pareto front", {}, {}, {{214, 39, 40}}};
      fem.markers = springs.markers = front.markers = true;
      fem.line = springs.line = false;
      std::vector<const SweepPoint *> on_front;
      for (const SweepPoint &point : points)
        {
          if (point.status != "completed")
            continue;
          io::PlotSeries &series =
            value_of(point.setting, "Model") == "mass-spring" ? springs : fem;
          series.x.push_back(point.run.wall_seconds);
          series.y.push_back(point.error);
          if (point.on_front)
            on_front.push_back(&point);
        }
      std::sort(on_front.begin(), on_front.end(), [](const auto *a, const auto *b) {
        return a->run.wall_seconds < b->run.wall_seconds;
      });
      for (const SweepPoint *point : on_front)
        {
          front.x.push_back(point->run.wall_seconds);
          front.y.push_back(point->error);
        }
      for (const io::PlotSeries *series : {&fem, &springs, &front})
        if (!series->x.empty())
          panel.series.push_back(*series);
      return io::write_line_plot(file, {panel}, 800, 500);
    }

    // For each decade of error the sweep reaches: the fastest setting within it.
    void
    print_fastest(const std::vector<SweepPoint> &points, std::ostream &out)
    {
      double low = std::numeric_limits<double>::infinity(), high = 0.;
      for (const SweepPoint &point : points)
        if (point.status == "completed" && point.error > 0.)
          {
            low  = std::min(low, point.error);
            high = std::max(high, point.error);
          }
      if (!(high > 0.))
        return;
      out << "fastest setting for each error level:\n";
      for (int k = std::ceil(std::log10(high)); k >= std::floor(std::log10(low)) + 1; --k)
        {
          const double      level   = std::pow(10., k);
          const SweepPoint *fastest = nullptr;
          for (const SweepPoint &point : points)
            if (point.status == "completed" && point.error <= level &&
                (fastest == nullptr ||
                 point.run.wall_seconds < fastest->run.wall_seconds))
              fastest = &point;
          if (fastest != nullptr)
            out << "  error <= " << level << " m: " << joined(fastest->setting) << " ("
                << fastest->run.wall_seconds << " s, error " << fastest->error << " m)\n";
        }
    }
  } // namespace


  std::vector<std::vector<std::string>>
  sweep_settings(const std::vector<std::string> &axes)
  {
    std::vector<std::vector<std::string>> grid = {{}};
    for (const std::string &axis : axes)
      {
        std::vector<std::vector<std::string>> alternatives;
        for (const std::string &alternative : Utilities::split_string_list(axis, '|'))
          {
            std::vector<std::string> assignments;
            for (const std::string &assignment :
                 Utilities::split_string_list(alternative, '&'))
              {
                if (assignment.find('=') == std::string::npos)
                  throw InputError("--axis",
                                   axis,
                                   "'" + assignment +
                                     "' is not an assignment \"Section/Name=value\"");
                assignments.push_back(assignment);
              }
            if (assignments.empty())
              throw InputError("--axis", axis, "an alternative is empty");
            alternatives.push_back(assignments);
          }
        if (alternatives.empty())
          throw InputError("--axis", axis, "no alternatives");
        std::vector<std::vector<std::string>> combined;
        for (const auto &setting : grid)
          for (const auto &alternative : alternatives)
            {
              auto extended = setting;
              extended.insert(extended.end(), alternative.begin(), alternative.end());
              combined.push_back(extended);
            }
        grid = combined;
      }
    return grid;
  }


  int
  run_speed_accuracy_sweep(const CommandLine  &command_line,
                           const std::string  &file,
                           const std::string  &directory,
                           const MPI_Comm      communicator,
                           ConditionalOStream &pcout)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    // The scene as given: its step sets the default grid and the reference's step.
    const std::unique_ptr<Scene> base =
      load_scene(file, command_line.overrides, communicator);
    const double scene_step = base->parameters().time.time_step;

    auto grid = sweep_settings(command_line.sweep_axes);
    if (command_line.sweep_axes.empty())
      {
        const std::string models = "Model=fem | Model=mass-spring";
        grid                     = sweep_settings(
          {models,
                               "Time/Integrator=backward euler | Time/Integrator=bdf2 | "
                                                   "Time/Integrator=implicit midpoint",
                               "Time/Time step=" + parameter_value(2. * scene_step) +
                                 " | Time/Time step=" + parameter_value(scene_step) +
                                 " | Time/Time step=" + parameter_value(0.5 * scene_step),
                               "Nonlinear solver/Method=newton | Nonlinear solver/Method=modified "
                                                   "newton | Nonlinear solver/Method=single step"});
        // The accuracy target with the second-order energy-conserving method (with
        // backward Euler a millimetre over seconds takes thousands of steps).
        for (const auto &setting :
             sweep_settings({models,
                             "Time/Integrator=implicit midpoint & Time/Accuracy "
                             "target=0.001",
                             "Nonlinear solver/Method=newton | Nonlinear "
                             "solver/Method=modified newton"}))
          grid.push_back(setting);
      }

    // The reference: an eighth of the smallest step, the finest mesh of the grid.
    double       smallest_step = scene_step;
    unsigned int finest_level  = base->parameters().scene.global_refinements;
    for (const auto &setting : grid)
      {
        const std::string step = value_of(setting, "Time/Time step");
        if (!step.empty())
          smallest_step = std::min(smallest_step, std::stod(step));
        const std::string level = value_of(setting, "Mesh/Global refinements");
        if (!level.empty())
          finest_level = std::max<unsigned int>(finest_level, std::stoi(level));
      }
    SweepPoint reference;
    reference.setting = {"Model=fem",
                         "Time/Integrator=implicit midpoint",
                         "Nonlinear solver/Method=newton",
                         "Time/Adaptive time steps=false",
                         "Time/Accuracy target=0",
                         "Time/Time step=" + parameter_value(smallest_step / 8.),
                         "Mesh/Global refinements=" + std::to_string(finest_level)};
    reference.setting.insert(reference.setting.end(),
                             command_line.reference_overrides.begin(),
                             command_line.reference_overrides.end());
    const auto with_base = [&command_line](const std::vector<std::string> &setting) {
      std::vector<std::string> overrides = command_line.overrides;
      overrides.insert(overrides.end(), setting.begin(), setting.end());
      return overrides;
    };

    pcout << "sweep of " << file << ": " << grid.size() << " settings and a reference ("
          << joined(reference.setting) << ")" << std::endl;
    pcout << "reference ..." << std::flush;
    reference.run    = run_study_case(file,
                                   with_base(reference.setting),
                                   directory + "/reference",
                                   communicator);
    reference.status = reference.run.completed ? "completed" : "failed";
    reference.error = reference.rms_error = 0.;
    pcout << " " << reference.status << " in " << reference.run.wall_seconds << " s"
          << std::endl;
    if (!reference.run.completed)
      {
        pcout << "the reference failed (" << reference.run.failure
              << "); no errors can be measured" << std::endl;
        return 2;
      }

    std::vector<SweepPoint> points;
    for (unsigned int n = 0; n < grid.size(); ++n)
      {
        SweepPoint point;
        point.setting = grid[n];
        std::ostringstream name;
        name << directory << "/run-" << std::setw(3) << std::setfill('0') << n;
        pcout << "[" << n + 1 << "/" << grid.size() << "] " << joined(point.setting)
              << " ..." << std::flush;
        try
          {
            point.run =
              run_study_case(file, with_base(point.setting), name.str(), communicator);
            point.status = point.run.completed ? "completed" : "failed";
          }
        catch (const InputError &error)
          {
            // A combination the parameters refuse (e.g. springs with consistent mass).
            point.status      = "invalid input";
            point.run.failure = error.what();
          }
        if (point.status == "completed" && is_root)
          {
            const FieldDifference difference =
              field_difference(point.run.vertices, reference.run.vertices);
            point.error     = difference.largest;
            point.rms_error = difference.rms;
          }
        pcout << " " << point.status;
        if (point.status == "completed")
          pcout << ", " << point.run.wall_seconds << " s, error " << point.error << " m";
        else
          pcout << ": " << point.run.failure;
        pcout << std::endl;
        points.push_back(std::move(point));
      }

    io::run_collectively(communicator, [&]() {
      if (is_root)
        {
          mark_front(points);
          write_csv(points, reference, directory + "/pareto.csv");
          const bool plotted = write_plot(points, directory + "/pareto.png");
          std::cout << "Pareto front (runtime, error at the end):\n";
          std::vector<const SweepPoint *> front;
          for (const SweepPoint &point : points)
            if (point.on_front)
              front.push_back(&point);
          std::sort(front.begin(), front.end(), [](const auto *a, const auto *b) {
            return a->run.wall_seconds < b->run.wall_seconds;
          });
          for (const SweepPoint *point : front)
            std::cout << "  " << std::setw(9) << point->run.wall_seconds << " s  "
                      << std::setw(12) << point->error << " m  " << joined(point->setting)
                      << "\n";
          print_fastest(points, std::cout);
          std::cout << "wrote " << directory << "/pareto.csv"
                    << (plotted ? " and pareto.png, .svg" : "") << std::endl;
        }
    });
    return 0;
  }
} // namespace clothsim
