#pragma once

// Minimal PNG line plots (plain C++17 + zlib): panels of x-y series stacked vertically,
// each with an axes box, "nice" ticks, grid, legend and title, drawn with a built-in
// bitmap font; linear or logarithmic axes, lines and/or markers. Used to compare probe
// histories of two runs, for log-log convergence plots and speed-accuracy scatter charts.

#include <array>
#include <string>
#include <vector>

namespace clothsim::io
{
  struct PlotSeries
  {
    std::string                  label; // legend text (ASCII); empty: not in the legend
    std::vector<double>          x, y;  // same length; non-finite points break the line
    std::array<unsigned char, 3> color; // RGB
    bool                         dashed = false;
    // A filled disc about 6 px across at every drawn point; the legend shows it too.
    bool markers = false;
    // Connect consecutive drawn points. false: a scatter series (with markers = false
    // too, every point is a 2 x 2 dot).
    bool line = true;
  };

  // One axes box.
  struct PlotPanel
  {
    std::string             title; // drawn above the box
    std::string             x_label;
    std::string             y_label; // drawn vertically left of the box
    std::vector<PlotSeries> series;
    // Logarithmic (base 10) axes: data are mapped through log10, points with a
    // non-positive coordinate on a log axis are skipped like non-finite ones (they break
    // the line). Ticks at the decades, labelled "1e-3", ..., with unlabelled minor grid
    // lines at 2..9 x 10^k where they are at least 3 px apart (at the skipped decades if
    // there are too many decades to label); a range too narrow for two decades gets
    // labelled ticks at 2 and 5 x 10^k, then at 1..9 x 10^k, then at a linear "nice"
    // step.
    bool log_x = false, log_y = false;
  };

  // Writes a PNG of the panels stacked vertically, each width x panel_height pixels,
  // every panel scaled to its own data with a 5% margin (in log10 space on a log axis).
  // Throws std::invalid_argument for no panels or a size too small to draw,
  // std::runtime_error naming the file if it cannot be written.
  void
  write_line_plot(const std::string            &file,
                  const std::vector<PlotPanel> &panels,
                  unsigned int                  width        = 800,
                  unsigned int                  panel_height = 300);
} // namespace clothsim::io
