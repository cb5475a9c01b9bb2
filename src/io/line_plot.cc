// Line plots: the data file and the gnuplot script (io/line_plot.h); running gnuplot is
// in io/line_plot_gnuplot.cc.

#include "io/line_plot.h"

#include "io/output_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace clothsim::io
{
  namespace
  {
    // A number to 17 significant digits (read back exactly).
    std::string
    exact(const double value)
    {
      char text[32];
      std::snprintf(text, sizeof(text), "%.17g", value);
      return text;
    }

    // A gnuplot string in double quotes: backslashes and quotes escaped.
    std::string
    quoted(const std::string &text)
    {
      std::string result = "\"";
      for (const char c : text)
        {
          if (c == '"' || c == '\\')
            result += '\\';
          result += c;
        }
      return result + '"';
    }

    std::string
    hex_color(const std::array<unsigned char, 3> &color)
    {
      char text[8];
      std::snprintf(text, sizeof(text), "#%02x%02x%02x", color[0], color[1], color[2]);
      return text;
    }

    bool
    drawable(const double x, const double y, const PlotPanel &panel)
    {
      return std::isfinite(x) && std::isfinite(y) && (!panel.log_x || x > 0.) &&
             (!panel.log_y || y > 0.);
    }

    // One block of the data file: what it draws and how.
    struct Block
    {
      std::string         title; // legend text, "" for none
      std::string         style; // gnuplot "with ..." clause
      std::vector<double> x, y;
    };

    // The reference slope y = C x^p over the first series' drawable x range, through the
    // centre of its points in log space; empty if there are fewer than two points.
    Block
    reference_slope(const PlotPanel &panel, const double order, const unsigned int number)
    {
      // Dotted, dash-dotted, ...; dark and light grey: told apart from each other and
      // from the data.
      Block block{"order " + exact(order),
                  "lines dt " + std::to_string(3 + number % 3) + " lw 1.5 lc rgb \"" +
                    (number % 2 == 0 ? "#606060" : "#a0a0a0") + "\"",
                  {},
                  {}};
      if (panel.series.empty())
        return block;
      const PlotSeries &series    = panel.series.front();
      double            sum_log_x = 0., sum_log_y = 0.;
      double            low = std::numeric_limits<double>::infinity(), high = -low;
      unsigned int      n_points = 0;
      for (std::size_t i = 0; i < series.x.size(); ++i)
        if (drawable(series.x[i], series.y[i], panel) && series.x[i] > 0. &&
            series.y[i] > 0.)
          {
            sum_log_x += std::log(series.x[i]);
            sum_log_y += std::log(series.y[i]);
            low  = std::min(low, series.x[i]);
            high = std::max(high, series.x[i]);
            ++n_points;
          }
      if (n_points < 2 || !(low < high))
        return block;
      const double coefficient =
        std::exp(sum_log_y / n_points - order * sum_log_x / n_points);
      block.x = {low, high};
      block.y = {coefficient * std::pow(low, order), coefficient * std::pow(high, order)};
      return block;
    }

    std::vector<Block>
    blocks_of(const PlotPanel &panel)
    {
      std::vector<Block> blocks;
      for (const PlotSeries &series : panel.series)
        {
          Block             block{series.label, "", series.x, series.y};
          const std::string color = " lc rgb \"" + hex_color(series.color) + "\"";
          const std::string dash  = series.dashed ? " dt 2" : " dt 1";
          if (series.line && series.markers)
            block.style = "linespoints pt 7 ps 0.8 lw 2" + dash + color;
          else if (series.line)
            block.style = "lines lw 2" + dash + color;
          else if (series.markers)
            block.style = "points pt 7 ps 1" + color;
          else
            block.style = "points pt 7 ps 0.3" + color;
          blocks.push_back(block);
        }
      if (panel.log_x && panel.log_y)
        for (unsigned int k = 0; k < panel.reference_orders.size(); ++k)
          blocks.push_back(reference_slope(panel, panel.reference_orders[k], k));
      return blocks;
    }

    // Decades the drawable values of one coordinate span (0 if none).
    double
    decades(const std::vector<Block> &blocks, const bool use_x)
    {
      double low = std::numeric_limits<double>::infinity(), high = 0.;
      for (const Block &block : blocks)
        for (const double value : use_x ? block.x : block.y)
          if (std::isfinite(value) && value > 0.)
            {
              low  = std::min(low, value);
              high = std::max(high, value);
            }
      return high > 0. ? std::log10(high / low) : 0.;
    }

    // The axis' scale and tick labels.
    void
    write_axis(std::ostream             &script,
               const char               *axis,
               const bool                log,
               const std::vector<Block> &blocks)
    {
      const bool use_x = axis[0] == 'x';
      if (!log)
        {
          script << "unset logscale " << axis << "\nset format " << axis
                 << " \"%g\"\nset " << axis << "tics autofreq\nset m" << axis
                 << "tics default\n";
          return;
        }
      script << "set logscale " << axis << " 10\n";
      // 10^k at the decades when there are decades to label; within one, gnuplot's own
      // ticks as plain numbers.
      if (decades(blocks, use_x) >= 1.)
        script << "set format " << axis << " \"10^{%L}\"\nset " << axis
               << "tics 10\nset m" << axis << "tics 10\n";
      else
        script << "set format " << axis << " \"%g\"\nset " << axis
               << "tics autofreq\nset m" << axis << "tics default\n";
    }

    // The drawing commands, the same for every terminal.
    void
    write_panels(std::ostream                          &script,
                 const std::vector<PlotPanel>          &panels,
                 const std::vector<std::vector<Block>> &blocks,
                 const std::string                     &data,
                 const unsigned int                     width,
                 const unsigned int                     height)
    {
      // Margins in pixels, the same for every panel so that the boxes line up: 85 left
      // for the tick labels and the y label, on the right room for the longest legend
      // entry (at most 8 px a character at 11 pt, 90 for the sample and gaps; at most
      // half the width), 45 above for the title, 65 below and 120 between panels for the
      // tick labels, the x label and the next title.
      std::size_t longest = 0;
      for (const auto &panel_blocks : blocks)
        for (const Block &block : panel_blocks)
          longest = std::max(longest, block.title.size());
      const double legend = std::min(0.5 * width, 90. + 8. * longest);
      script << "set multiplot layout " << panels.size() << ",1 margins " << 85. / width
             << ", " << 1. - (legend + 15.) / width << ", " << 65. / height << ", "
             << 1. - 45. / height << " spacing 0, " << 120. / height << "\n"
             << "set key at screen " << 1. - legend / width
             << ", graph 1 left top vertical Left reverse samplen 3\n";
      unsigned int index = 0;
      for (std::size_t p = 0; p < panels.size(); ++p)
        {
          const PlotPanel &panel = panels[p];
          script << "\n# panel " << p + 1 << "\nset title " << quoted(panel.title)
                 << " noenhanced\nset xlabel " << quoted(panel.x_label)
                 << " noenhanced\nset ylabel " << quoted(panel.y_label)
                 << " noenhanced\n";
          write_axis(script, "x", panel.log_x, blocks[p]);
          write_axis(script, "y", panel.log_y, blocks[p]);
          std::vector<std::string> plots;
          for (const Block &block : blocks[p])
            {
              if (!block.x.empty())
                plots.push_back(quoted(data) + " index " + std::to_string(index) +
                                " using 1:2 with " + block.style +
                                (block.title.empty()
                                   ? " notitle"
                                   : " title " + quoted(block.title) + " noenhanced"));
              index += block.x.empty() ? 0 : 1;
            }
          if (plots.empty())
            {
              // Nothing to draw: an empty box that says so.
              script << "unset logscale xy\nset label 1 \"no data\" at graph 0.5, 0.5 "
                        "center\nplot [0:1] [0:1] NaN notitle\nunset label 1\n";
              continue;
            }
          script << "plot ";
          for (std::size_t k = 0; k < plots.size(); ++k)
            script << (k == 0 ? "" : ", \\\n     ") << plots[k];
          script << '\n';
        }
      script << "unset multiplot\n";
    }
  } // namespace


  bool
  write_line_plot(const std::string            &file,
                  const std::vector<PlotPanel> &panels,
                  const unsigned int            width,
                  const unsigned int            panel_height)
  {
    if (panels.empty())
      throw std::invalid_argument("write_line_plot: no panels for " + file);
    if (width < 200 || panel_height < 100)
      throw std::invalid_argument("write_line_plot: " + std::to_string(width) + " x " +
                                  std::to_string(panel_height) +
                                  " pixels per panel is too small for " + file);
    const std::filesystem::path path(file);
    const std::string           directory =
      path.has_parent_path() ? path.parent_path().string() : std::string(".");
    const std::string stem = path.stem().string();
    const std::string data = stem + ".dat", script_name = stem + ".gp";
    const std::string png = path.filename().string(), svg = stem + ".svg";

    std::vector<std::vector<Block>> blocks;
    for (const PlotPanel &panel : panels)
      blocks.push_back(blocks_of(panel));

    // The data: one block per drawn line, separated by two blank lines (gnuplot's
    // "index"); a blank line inside a block where a point cannot be drawn.
    write_file_atomically(directory + "/" + data, [&](std::ostream &out) {
      out << "# " << data << ": written by clothsim for " << png
          << "; one block per line drawn (gnuplot index 0, 1, ...): x y\n";
      unsigned int index = 0;
      for (std::size_t p = 0; p < panels.size(); ++p)
        for (const Block &block : blocks[p])
          {
            if (block.x.empty())
              continue;
            out << (index == 0 ? "" : "\n\n") << "# index " << index << ": panel "
                << p + 1 << ", " << (block.title.empty() ? "(no title)" : block.title)
                << '\n';
            for (std::size_t i = 0; i < block.x.size(); ++i)
              {
                const double y = i < block.y.size() ? block.y[i] : std::nan("");
                if (drawable(block.x[i], y, panels[p]))
                  out << exact(block.x[i]) << ' ' << exact(y) << '\n';
                else
                  out << '\n';
              }
            ++index;
          }
    });

    const unsigned int height = panel_height * panels.size();
    write_file_atomically(directory + "/" + script_name, [&](std::ostream &out) {
      out << "# " << script_name << ": written by clothsim; draws " << png << " and "
          << svg << " from " << data << ".\n# Run in this directory: gnuplot "
          << script_name
          << "\n# (clothsim passes -e \"suffix='.partial'\" and renames the files when "
             "done)\nif (!exists(\"suffix\")) suffix = \"\"\n"
          << "set encoding utf8\nset grid xtics ytics mxtics mytics lc rgb \"#e0e0e0\" "
             "lw 1, lc "
             "rgb \"#f0f0f0\" lw 1\nset border lw 1.2\nset tics nomirror out\n";
      const std::string terminals[2][2] = {
        {"pngcairo enhanced background rgb \"white\" font \"DejaVu Sans,11\"", png},
        {"svg enhanced background rgb \"white\" font \"DejaVu Sans,11\"", svg}};
      for (const auto &[terminal, output] : terminals)
        {
          out << "\nset terminal " << terminal << " size " << width << ',' << height
              << "\nset output " << quoted(output) << ".suffix\n";
          write_panels(out, panels, blocks, data, width, height);
          out << "unset output\n";
        }
    });

    // gnuplot writes *.partial; the pictures are renamed once both are complete.
    const std::string reason = run_gnuplot(directory,
                                           {"-e", "suffix='.partial'", script_name},
                                           directory + "/" + stem + ".gnuplot.log");
    bool              drawn  = reason.empty();
    for (const std::string &picture : {png, svg})
      {
        const std::string partial = directory + "/" + picture + ".partial";
        std::error_code   error;
        if (drawn)
          std::filesystem::rename(partial, directory + "/" + picture, error);
        else
          std::filesystem::remove(partial, error);
        drawn = drawn && !error;
      }
    if (drawn)
      {
        std::error_code ignored;
        std::filesystem::remove(directory + "/" + stem + ".gnuplot.log", ignored);
      }
    else
      std::cerr << "clothsim: warning: " << file << " not drawn: "
                << (reason.empty() ? std::string("cannot rename the pictures") : reason)
                << "; the data and the script are in " << directory << "/" << data
                << " and " << script_name << std::endl;
    return drawn;
  }
} // namespace clothsim::io
