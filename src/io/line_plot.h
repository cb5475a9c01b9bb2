#pragma once

// Line plots drawn by gnuplot (Debian package gnuplot-nox): panels of x-y series stacked
// vertically, each with a title, axis labels, a legend outside the axes, linear or
// logarithmic axes (labelled decades), lines and/or markers, and optional reference
// slopes y = C x^p. For `DIR/name.png` the program writes the data `DIR/name.dat` and the
// script `DIR/name.gp` beside it and runs gnuplot there, which draws `DIR/name.png` and
// `DIR/name.svg`; `cd DIR && gnuplot name.gp` draws them again (e.g. after editing the
// script). Used to compare probe histories of two runs, for log-log convergence plots and
// speed-accuracy scatter charts.

#include <array>
#include <string>
#include <vector>

namespace clothsim::io
{
  struct PlotSeries
  {
    std::string                  label; // legend text; empty: not in the legend
    std::vector<double>          x, y;  // same length; non-finite points break the line
    std::array<unsigned char, 3> color; // RGB
    bool                         dashed = false;
    // A filled disc at every point; the legend shows it too.
    bool markers = false;
    // Connect consecutive points. false: a scatter series (with markers = false too,
    // small dots).
    bool line = true;
  };

  // One axes box.
  struct PlotPanel
  {
    std::string             title;
    std::string             x_label; // with the unit, e.g. "time (s)"
    std::string             y_label;
    std::vector<PlotSeries> series;
    // Logarithmic (base 10) axes: points with a non-positive coordinate on a log axis
    // are skipped like non-finite ones (they break the line). Ticks at the decades,
    // labelled 10^k, when the data span at least one decade.
    bool log_x = false, log_y = false;
    // Reference slopes on a log-log panel: for each order p a grey dashed line
    // y = C x^p over the first series' x range, through the centre (in log space) of its
    // points, in the legend as "order p".
    std::vector<double> reference_orders;
  };

  // Writes DIR/name.dat and DIR/name.gp for `file` = DIR/name.png and runs gnuplot,
  // which draws the panels stacked vertically, each width x panel_height pixels, into
  // `file` and DIR/name.svg (each written whole, under a temporary name first). Returns
  // whether the pictures were drawn: if gnuplot is missing or fails, prints a warning
  // naming the plot, the reason and the data and script written, to std::cerr, and
  // returns false (a plot is a view of the CSV files, which are the results).
  // Throws std::invalid_argument for no panels or a size too small to draw (below
  // 200 x 100), OutputError if the data or script cannot be written.
  bool
  write_line_plot(const std::string            &file,
                  const std::vector<PlotPanel> &panels,
                  unsigned int                  width        = 800,
                  unsigned int                  panel_height = 300);

  // Runs `gnuplot` with `arguments` in `directory` (found on PATH), stdout and stderr
  // into `log_file` (removed again if gnuplot cannot be started). Returns "" on success,
  // else the reason ("gnuplot not found on PATH (Debian package gnuplot-nox)", the exit
  // status and the log's first lines).
  std::string
  run_gnuplot(const std::string              &directory,
              const std::vector<std::string> &arguments,
              const std::string              &log_file);
} // namespace clothsim::io
