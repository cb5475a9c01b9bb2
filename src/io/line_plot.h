#pragma once

// Minimal PNG line plots (plain C++17 + zlib): panels of x-y series stacked vertically,
// each with an axes box, "nice" ticks, grid, legend and title, drawn with a built-in
// bitmap font. Used to compare probe histories of two runs.

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
  };

  // One axes box.
  struct PlotPanel
  {
    std::string             title; // drawn above the box
    std::string             x_label;
    std::string             y_label; // drawn vertically left of the box
    std::vector<PlotSeries> series;
  };

  // Writes a PNG of the panels stacked vertically, each width x panel_height pixels,
  // every panel scaled to its own data with a 5% margin. Throws std::invalid_argument for
  // no panels or a size too small to draw, std::runtime_error naming the file if it
  // cannot be written.
  void
  write_line_plot(const std::string            &file,
                  const std::vector<PlotPanel> &panels,
                  unsigned int                  width        = 800,
                  unsigned int                  panel_height = 300);
} // namespace clothsim::io
