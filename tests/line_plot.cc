// Unit test of clothsim::io::write_line_plot (gnuplot): what the program hands gnuplot
// and what gnuplot makes of it.
//  - A two-panel linear plot: the data file holds one block per series with every value
//    to 17 digits and a blank line (a break in the line) at a non-finite point; the
//    script has the titles and axis labels, a multiplot of 2 panels, the legend outside
//    the axes, the pngcairo and svg terminals at 800 x 2 * 250; gnuplot drew a PNG of
//    exactly that size (read from its IHDR) and an SVG, and no temporary files are left.
//  - A log-log panel with reference orders 1 and 2: logarithmic axes labelled 10^k at the
//    decades, a non-positive point skipped, the slope lines as data blocks "order 1" and
//    "order 2" whose slope in log space is the order and which pass through the centre of
//    the first series' points; a one-decade panel gets plain tick labels.
//  - gnuplot missing from PATH: the data and the script are written, no picture, false
//    returned and a warning that names the plot and the Debian package.
//  - Errors: no panels and a size too small throw std::invalid_argument; a directory that
//    does not exist throws OutputError.
// With an argument, the files are kept in that directory.

#include "io/line_plot.h"
#include "io/output_file.h"
#include "test_support.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace clothsim::io;
using namespace clothsim::test;

namespace
{
  std::string
  read_text(const std::string &path)
  {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)),
                       std::istreambuf_iterator<char>());
  }

  bool
  contains(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
  }

  // Width and height from a PNG's signature and IHDR chunk; {0, 0} if it is not a PNG.
  std::pair<unsigned int, unsigned int>
  png_size(const std::string &path)
  {
    const std::string bytes = read_text(path);
    if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 ||
        bytes.compare(12, 4, "IHDR") != 0)
      return {0, 0};
    const auto big_endian = [&](const std::size_t at) {
      unsigned int value = 0;
      for (std::size_t k = 0; k < 4; ++k)
        value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
      return value;
    };
    return {big_endian(16), big_endian(20)};
  }

  // The data blocks (separated by two blank lines) as lists of lines, comments dropped.
  std::vector<std::vector<std::string>>
  data_blocks(const std::string &path)
  {
    std::vector<std::vector<std::string>> blocks(1);
    std::istringstream                    in(read_text(path));
    std::string                           line;
    unsigned int                          n_blank = 0;
    while (std::getline(in, line))
      {
        if (line.rfind('#', 0) == 0)
          continue;
        if (line.empty() && ++n_blank == 2)
          {
            blocks.emplace_back();
            n_blank = 0;
            continue;
          }
        if (!line.empty() && n_blank == 1)
          blocks.back().push_back("");
        if (!line.empty())
          {
            n_blank = 0;
            blocks.back().push_back(line);
          }
      }
    return blocks;
  }

  std::string
  joined(const std::vector<std::string> &lines)
  {
    std::string result;
    for (std::size_t k = 0; k < lines.size(); ++k)
      result += (k == 0 ? "" : "|") + lines[k];
    return result;
  }

  std::pair<double, double>
  point_of(const std::string &line)
  {
    std::istringstream in(line);
    double             x = std::nan(""), y = std::nan("");
    in >> x >> y;
    return {x, y};
  }

  PlotPanel
  make_panel(const std::string &title,
             const std::string &x_label,
             const std::string &y_label)
  {
    PlotPanel panel;
    panel.title   = title;
    panel.x_label = x_label;
    panel.y_label = y_label;
    return panel;
  }

  PlotSeries
  series(const std::string         &label,
         const std::vector<double> &x,
         const std::vector<double> &y,
         const bool                 markers)
  {
    PlotSeries result{label, x, y, {{31, 119, 180}}};
    result.markers = markers;
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &out  = env.pcout;
  const bool          keep = argc > 1;
  const std::string   directory =
    keep ? std::string(argv[1])
           : scratch_directory("clothsim-line-plot-" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  const double nan = std::numeric_limits<double>::quiet_NaN();

  // A two-panel linear plot.
  {
    PlotPanel top = make_panel("probe tip", "time (s)", "uz (m)");
    top.series.push_back(
      series("fem", {0., 0.1, 0.2, 0.3}, {0., -0.25, nan, -0.5}, false));
    top.series.push_back(series("mass-spring", {0., 0.1}, {1. / 3., 2. / 3.}, true));
    top.series.back().dashed = true;
    PlotPanel bottom         = make_panel("probe \"corner\"", "time (s)", "ux (m)");
    bottom.series.push_back(series("fem", {0., 1.}, {1e-3, 2e-3}, false));
    const bool drawn = write_line_plot(directory + "/two.png", {top, bottom}, 800, 250);
    check(out, drawn, "two panels: drawn");

    const auto blocks = data_blocks(directory + "/two.dat");
    check_equal(out, "two panels: data blocks", blocks.size(), std::size_t(3));
    if (blocks.size() == 3)
      {
        check_equal(out,
                    "two panels: first series' lines (a blank at the NaN)",
                    joined(blocks[0]),
                    std::string(
                      "0 0|0.10000000000000001 -0.25||0.29999999999999999 -0.5"));
        check_equal(out,
                    "two panels: second series to 17 digits",
                    joined(blocks[1]),
                    std::string(
                      "0 0.33333333333333331|0.10000000000000001 0.66666666666666663"));
      }
    const std::string script = read_text(directory + "/two.gp");
    for (const std::string &part :
         {std::string("set multiplot layout 2,1"),
          std::string("set title \"probe tip\" noenhanced"),
          std::string("set title \"probe \\\"corner\\\"\" noenhanced"),
          std::string("set xlabel \"time (s)\""),
          std::string("set ylabel \"uz (m)\""),
          std::string("set terminal pngcairo"),
          std::string("set terminal svg"),
          std::string("size 800,500"),
          std::string("\"two.dat\" index 0 using 1:2 with lines lw 2 dt 1 lc rgb "
                      "\"#1f77b4\" title \"fem\""),
          std::string("index 1 using 1:2 with linespoints pt 7 ps 0.8 lw 2 dt 2"),
          std::string("title \"mass-spring\""),
          std::string("unset logscale x")})
      check(out, contains(script, part), "two panels: script has '" + part + "'");
    // The legend right of the axes: the key's left edge beyond the panels' right margin.
    double     left = 0., right = 0., lower = 0., upper = 0., key_x = 0.;
    const auto layout = script.find("set multiplot layout 2,1 margins ");
    const auto key    = script.find("set key at screen ");
    if (layout != std::string::npos)
      std::sscanf(script.c_str() + layout,
                  "set multiplot layout 2,1 margins %lf, %lf, %lf, %lf",
                  &left,
                  &right,
                  &lower,
                  &upper);
    if (key != std::string::npos)
      std::sscanf(script.c_str() + key, "set key at screen %lf", &key_x);
    check(out,
          left > 0. && left < right && right < key_x && key_x < 1. && lower < upper,
          "two panels: margins " + std::to_string(left) + " to " + std::to_string(right) +
            ", the legend at " + std::to_string(key_x) + " (screen), outside the axes");
    const auto size = png_size(directory + "/two.png");
    check_equal(out, "two panels: PNG width", size.first, 800u);
    check_equal(out, "two panels: PNG height", size.second, 500u);
    const std::string svg = read_text(directory + "/two.svg");
    check(out,
          contains(svg, "<svg") && contains(svg, "width=\"800\"") &&
            contains(svg, "height=\"500\"") && contains(svg, "probe tip"),
          "two panels: SVG of 800 x 500 with the title");
    check(out,
          !std::filesystem::exists(directory + "/two.png.partial") &&
            !std::filesystem::exists(directory + "/two.svg.partial") &&
            !std::filesystem::exists(directory + "/two.gnuplot.log"),
          "two panels: no temporary files left");
  }

  // A log-log panel with reference slopes: errors of order 2 with one bad point.
  {
    PlotPanel panel = make_panel("space convergence", "mesh size h/h0", "error (m)");
    panel.log_x = panel.log_y = true;
    panel.reference_orders    = {1., 2.};
    panel.series.push_back(series("probe:tip",
                                  {1., 0.5, 0.25, 0.125, 0.0625},
                                  {1e-2, 2.5e-3, 0., 1.5625e-4, 3.90625e-5},
                                  true));
    PlotPanel narrow = make_panel("one decade", "runtime (s)", "error (m)");
    narrow.log_x = narrow.log_y = true;
    narrow.series.push_back(series("fem", {2., 3., 5.}, {0.2, 0.3, 0.5}, true));
    check(out,
          write_line_plot(directory + "/log.png", {panel, narrow}, 640, 400),
          "log: drawn");

    const auto blocks = data_blocks(directory + "/log.dat");
    // probe:tip, order 1, order 2 (panel 1), fem (panel 2); the narrow panel's series
    // has one decade at most, so no slopes are asked for there.
    check_equal(out, "log: data blocks", blocks.size(), std::size_t(4));
    if (blocks.size() == 4)
      {
        check_equal(out, "log: the zero error is a break", blocks[0][2], std::string(""));
        // The centre of the drawable points in log space.
        double sum_x = 0., sum_y = 0.;
        for (const auto &[x, y] : std::vector<std::pair<double, double>>{
               {1., 1e-2}, {0.5, 2.5e-3}, {0.125, 1.5625e-4}, {0.0625, 3.90625e-5}})
          {
            sum_x += std::log(x) / 4.;
            sum_y += std::log(y) / 4.;
          }
        for (const unsigned int order : {1u, 2u})
          {
            const auto &block = blocks[order];
            check_equal(out,
                        "log: order " + std::to_string(order) + " points",
                        block.size(),
                        std::size_t(2));
            if (block.size() != 2)
              continue;
            const auto [x0, y0] = point_of(block[0]);
            const auto [x1, y1] = point_of(block[1]);
            check_near(out,
                       "log: order " + std::to_string(order) + " line from x",
                       x0,
                       0.0625,
                       1e-15);
            check_near(
              out, "log: order " + std::to_string(order) + " line to x", x1, 1., 1e-15);
            check_near(out,
                       "log: order " + std::to_string(order) + " slope in log space",
                       std::log(y1 / y0) / std::log(x1 / x0),
                       double(order),
                       1e-12);
            check_near(out,
                       "log: order " + std::to_string(order) + " line through the centre",
                       std::log(y0) + order * (sum_x - std::log(x0)),
                       sum_y,
                       1e-12);
          }
      }
    const std::string script = read_text(directory + "/log.gp");
    for (const std::string &part : {std::string("set logscale x 10"),
                                    std::string("set logscale y 10"),
                                    std::string("set format x \"10^{%L}\""),
                                    std::string("set format y \"10^{%L}\""),
                                    std::string("title \"order 1\""),
                                    std::string("title \"order 2\""),
                                    std::string("set format y \"%g\""),
                                    std::string("set xlabel \"mesh size h/h0\""),
                                    std::string("set ylabel \"error (m)\"")})
      check(out, contains(script, part), "log: script has '" + part + "'");
    const auto size = png_size(directory + "/log.png");
    check_equal(out, "log: PNG width", size.first, 640u);
    check_equal(out, "log: PNG height", size.second, 800u);
  }

  // gnuplot missing.
  {
    const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
    setenv("PATH", (directory + "/no-such-directory").c_str(), 1);
    PlotPanel panel = make_panel("t", "x (m)", "y (m)");
    panel.series.push_back(series("a", {0., 1.}, {0., 1.}, false));
    std::ostringstream warning;
    auto *const        old_buffer = std::cerr.rdbuf(warning.rdbuf());
    const bool         drawn      = write_line_plot(directory + "/missing.png", {panel});
    std::cerr.rdbuf(old_buffer);
    setenv("PATH", path.c_str(), 1);
    check(out, !drawn, "no gnuplot: not drawn, no exception");
    check(out,
          std::filesystem::exists(directory + "/missing.dat") &&
            std::filesystem::exists(directory + "/missing.gp") &&
            !std::filesystem::exists(directory + "/missing.png"),
          "no gnuplot: data and script written, no PNG");
    check(out,
          contains(warning.str(), "missing.png not drawn") &&
            contains(warning.str(), "gnuplot-nox") &&
            contains(warning.str(), "missing.gp"),
          "no gnuplot: warning '" + warning.str().substr(0, warning.str().size() - 1) +
            "'");
  }

  // Errors.
  {
    PlotPanel panel = make_panel("t", "x", "y");
    panel.series.push_back(series("a", {0., 1.}, {0., 1.}, false));
    const auto throws = [&](const std::string &what, const auto &call) {
      try
        {
          call();
        }
      catch (const std::invalid_argument &)
        {
          return what == "invalid";
        }
      catch (const OutputError &)
        {
          return what == "output";
        }
      return false;
    };
    check(out,
          throws("invalid", [&]() { write_line_plot(directory + "/none.png", {}); }),
          "no panels: std::invalid_argument");
    check(out,
          throws("invalid",
                 [&]() { write_line_plot(directory + "/small.png", {panel}, 100, 100); }),
          "100 x 100: std::invalid_argument");
    check(out,
          throws("output",
                 [&]() { write_line_plot(directory + "/no/such/dir.png", {panel}); }),
          "missing directory: OutputError");
  }

  if (!keep)
    std::filesystem::remove_all(directory);
  return finish_tally(out);
}
