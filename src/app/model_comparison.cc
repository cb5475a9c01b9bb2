#include "app/model_comparison.h"

#include "io/line_plot.h"
#include "io/output_file.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace clothsim
{
  namespace
  {
    double
    distance(const std::array<double, 6> &a, const std::array<double, 6> &b)
    {
      double sum = 0.;
      for (unsigned int d = 3; d < 6; ++d)
        sum += (a[d] - b[d]) * (a[d] - b[d]);
      return std::sqrt(sum);
    }

    // The index of the frame of `trajectory` at `time`, or -1.
    int
    matching_frame(const Trajectory &trajectory, const double time)
    {
      for (unsigned int k = 0; k < trajectory.times.size(); ++k)
        if (std::abs(trajectory.times[k] - time) <= 1e-9 * std::max(1., std::abs(time)))
          return k;
      return -1;
    }
  } // namespace


  ComparisonFigures
  write_comparison(const std::string              &directory,
                   const ComparedRun              &fem,
                   const ComparedRun              &mass_spring,
                   const std::vector<std::string> &probe_names)
  {
    ComparisonFigures figures{};
    if (fem.trajectory.frames.empty() || mass_spring.trajectory.frames.empty())
      throw std::runtime_error("a run wrote no frame to compare");
    const auto &first = fem.trajectory.frames.front();
    if (first.size() != mass_spring.trajectory.frames.front().size())
      throw std::runtime_error("the two runs have different meshes");

    // Sheet size: the reference mesh's largest bounding-box side.
    for (unsigned int d = 0; d < 3; ++d)
      {
        const auto [low, high] =
          std::minmax_element(first.begin(),
                              first.end(),
                              [d](const auto &a, const auto &b) { return a[d] < b[d]; });
        figures.sheet_size = std::max(figures.sheet_size, (*high)[d] - (*low)[d]);
      }

    std::ostringstream csv;
    csv << "time,quantity,difference,relative_difference\n" << std::setprecision(10);
    // Probe histories for the plot: [probe][model] -> (times, displacement components).
    std::vector<std::array<std::vector<std::array<double, 4>>, 2>> histories(
      probe_names.size());
    for (unsigned int k = 0; k < fem.trajectory.times.size(); ++k)
      {
        const double time  = fem.trajectory.times[k];
        const int    other = matching_frame(mass_spring.trajectory, time);
        if (other < 0)
          continue;
        const auto &a           = fem.trajectory.frames[k];
        const auto &b           = mass_spring.trajectory.frames[other];
        double      sum_squares = 0., largest = 0.;
        for (unsigned int i = 0; i < a.size(); ++i)
          {
            const double gap = distance(a[i], b[i]);
            sum_squares += gap * gap;
            largest = std::max(largest, gap);
          }
        const double rms = std::sqrt(sum_squares / a.size());
        for (unsigned int p = 0; p < probe_names.size(); ++p)
          {
            const Tensor<1, 3> &u_fem = fem.trajectory.probes[k][p];
            const Tensor<1, 3> &u_ms  = mass_spring.trajectory.probes[other][p];
            const double        gap   = (u_fem - u_ms).norm();
            csv << time << ',' << probe_names[p] << ',' << gap << ','
                << gap / figures.sheet_size << '\n';
            histories[p][0].push_back({{time, u_fem[0], u_fem[1], u_fem[2]}});
            histories[p][1].push_back({{time, u_ms[0], u_ms[1], u_ms[2]}});
          }
        csv << time << ",mesh_rms," << rms << ',' << rms / figures.sheet_size << '\n'
            << time << ",mesh_max," << largest << ',' << largest / figures.sheet_size
            << '\n';
        ++figures.frames;
        figures.final_rms   = rms;
        figures.final_max   = largest;
        figures.largest_rms = std::max(figures.largest_rms, rms);
        figures.largest_max = std::max(figures.largest_max, largest);
      }

    io::write_file_atomically(directory + "/comparison.csv",
                              [&csv](std::ostream &out) { out << csv.str(); });
    std::ostringstream runtimes;
    runtimes << "model,integrator,time_step,steps,newton_iterations,wall_seconds,"
                "completed\n";
    for (const ComparedRun *run : {&fem, &mass_spring})
      runtimes << run->model << ',' << run->integrator << ',' << run->time_step << ','
               << run->summary.steps << ',' << run->summary.newton_iterations << ','
               << run->wall_seconds << ',' << (run->completed ? "true" : "false") << '\n';
    io::write_file_atomically(directory + "/runtimes.csv",
                              [&runtimes](std::ostream &out) { out << runtimes.str(); });

    // One panel per probe: the displacement component that moves most, both models.
    std::vector<io::PlotPanel> panels;
    for (unsigned int p = 0; p < probe_names.size(); ++p)
      {
        unsigned int component = 1;
        double       range     = -1.;
        for (unsigned int c = 1; c <= 3; ++c)
          {
            double low = 0., high = 0.;
            for (const auto &history : histories[p])
              for (const auto &row : history)
                {
                  low  = std::min(low, row[c]);
                  high = std::max(high, row[c]);
                }
            if (high - low > range)
              {
                range     = high - low;
                component = c;
              }
          }
        io::PlotPanel panel;
        panel.title   = "probe " + probe_names[p];
        panel.x_label = "time (s)";
        panel.y_label = std::string("u") + "xyz"[component - 1] + " (m)";
        for (unsigned int m = 0; m < 2; ++m)
          {
            io::PlotSeries series;
            series.label  = m == 0 ? "fem (" + fem.integrator + ")"
                                   : "mass-spring (" + mass_spring.integrator + ")";
            series.color  = m == 0 ? std::array<unsigned char, 3>{{31, 119, 180}}
                                   : std::array<unsigned char, 3>{{214, 39, 40}};
            series.dashed = m == 1;
            for (const auto &row : histories[p][m])
              {
                series.x.push_back(row[0]);
                series.y.push_back(row[component]);
              }
            panel.series.push_back(series);
          }
        panels.push_back(panel);
      }
    if (!panels.empty())
      io::write_line_plot(directory + "/comparison.png", panels, 800, 260);
    return figures;
  }
} // namespace clothsim
