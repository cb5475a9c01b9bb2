// Unit test of clothsim::io::write_line_plot: writes plots of known series, reads the PNG
// back (chunk CRCs, IHDR, inflated IDAT, filter bytes) and checks size, background,
// series colours, text, the position of y = x in its box, degenerate series and a bad
// path; then log axes and markers: marker positions of y = x^-2 on a log-log panel, no
// line between markers, skipped non-positive values, decade tick labels read back pixel
// by pixel, minor grid lines, narrow log ranges, legend samples of line and marker
// series. With arguments, the two-panel plot is kept at the first path, the log plot at
// the second.

#include "io/line_plot.h"
#include "test_support.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
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
  using Color = std::array<unsigned char, 3>;

  struct Png
  {
    unsigned int               width = 0, height = 0;
    std::vector<unsigned char> rgb;

    Color
    at(const unsigned int x, const unsigned int y) const
    {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
      return {{rgb[i], rgb[i + 1], rgb[i + 2]}};
    }
  };

  std::uint32_t
  read_u32(const std::string &bytes, const std::size_t at)
  {
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i)
      value = (value << 8) | static_cast<unsigned char>(bytes.at(at + i));
    return value;
  }

  // Reads an 8-bit RGB PNG as written by write_line_plot; throws on anything unexpected.
  Png
  read_png(const std::string &file)
  {
    std::ifstream     in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)),
                            std::istreambuf_iterator<char>());
    if (bytes.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0)
      throw std::runtime_error("no PNG signature");
    Png         png;
    std::string idat;
    bool        end = false;
    for (std::size_t at = 8; !end;)
      {
        const std::uint32_t length = read_u32(bytes, at);
        const std::string   type   = bytes.substr(at + 4, 4);
        const std::string   data   = bytes.substr(at + 8, length);
        if (data.size() != length)
          throw std::runtime_error("truncated chunk " + type);
        const std::uint32_t crc =
          crc32(0, reinterpret_cast<const Bytef *>(bytes.data() + at + 4), length + 4);
        if (crc != read_u32(bytes, at + 8 + length))
          throw std::runtime_error("bad CRC in chunk " + type);
        if (type == "IHDR")
          {
            png.width  = read_u32(data, 0);
            png.height = read_u32(data, 4);
            if (data.substr(8) != std::string("\x08\x02\x00\x00\x00", 5))
              throw std::runtime_error("not 8-bit RGB without interlace");
          }
        else if (type == "IDAT")
          idat += data;
        else if (type == "IEND")
          end = true;
        at += 12 + length;
      }

    const std::size_t          row_bytes = 1 + 3 * static_cast<std::size_t>(png.width);
    std::vector<unsigned char> raw(row_bytes * png.height);
    uLongf                     raw_size = raw.size();
    if (uncompress(raw.data(),
                   &raw_size,
                   reinterpret_cast<const Bytef *>(idat.data()),
                   idat.size()) != Z_OK ||
        raw_size != raw.size())
      throw std::runtime_error("IDAT does not inflate to the image size");
    for (unsigned int y = 0; y < png.height; ++y)
      {
        if (raw[y * row_bytes] != 0)
          throw std::runtime_error("unexpected filter type");
        png.rgb.insert(png.rgb.end(),
                       raw.begin() + y * row_bytes + 1,
                       raw.begin() + (y + 1) * row_bytes);
      }
    return png;
  }

  unsigned int
  count_color(const Png &png, const Color &c)
  {
    unsigned int n = 0;
    for (unsigned int y = 0; y < png.height; ++y)
      for (unsigned int x = 0; x < png.width; ++x)
        n += png.at(x, y) == c;
    return n;
  }

  bool
  dark(const Color &c)
  {
    return c[0] < 100 && c[1] < 100 && c[2] < 100;
  }

  unsigned int
  count_dark(const Png         &png,
             const unsigned int x0,
             const unsigned int y0,
             const unsigned int x1,
             const unsigned int y1)
  {
    unsigned int n = 0;
    for (unsigned int y = y0; y < y1; ++y)
      for (unsigned int x = x0; x < x1; ++x)
        n += dark(png.at(x, y));
    return n;
  }

  // Axes box in rows [y0, y1): the rows whose longest pure black run spans half the
  // width.
  struct Box
  {
    int left = -1, right = -1, top = -1, bottom = -1;
  };

  Box
  find_box(const Png &png, const unsigned int y0, const unsigned int y1)
  {
    Box box;
    for (unsigned int y = y0; y < y1; ++y)
      {
        int run = 0, best = 0, best_end = 0;
        for (unsigned int x = 0; x < png.width; ++x)
          {
            run = png.at(x, y) == Color{{0, 0, 0}} ? run + 1 : 0;
            if (run > best)
              {
                best     = run;
                best_end = x;
              }
          }
        if (best >= static_cast<int>(png.width) / 2)
          {
            if (box.top < 0)
              {
                box.top   = y;
                box.left  = best_end - best + 1;
                box.right = best_end;
              }
            box.bottom = y;
          }
      }
    return box;
  }

  // Centroid of the pixels of exactly colour c.
  std::array<double, 2>
  centroid(const Png &png, const Color &c)
  {
    double       sx = 0, sy = 0;
    unsigned int n = 0;
    for (unsigned int y = 0; y < png.height; ++y)
      for (unsigned int x = 0; x < png.width; ++x)
        if (png.at(x, y) == c)
          {
            sx += x;
            sy += y;
            ++n;
          }
    return {{sx / n, sy / n}};
  }

  // Glyphs of the plot's bitmap font for the characters of tick labels: 8 rows, bit 4 the
  // leftmost of 5 columns, 6 px advance.
  const std::string       glyph_chars   = "0123456789e-.";
  constexpr unsigned char glyphs[13][8] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E, 0x00}, // 0
    {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E, 0x00}, // 1
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F, 0x00}, // 2
    {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E, 0x00}, // 3
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02, 0x00}, // 4
    {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E, 0x00}, // 5
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E, 0x00}, // 6
    {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08, 0x00}, // 7
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E, 0x00}, // 8
    {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C, 0x00}, // 9
    {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E, 0x00}, // e
    {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00, 0x00}, // -
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C, 0x00}, // .
  };

  int
  text_width(const std::string &text)
  {
    return 6 * static_cast<int>(text.size()) - 1;
  }

  // Whether `text` is drawn in black with its top-left corner at (x0, y0): every pixel
  // of its cells, one pixel of white space around included, is dark exactly where a
  // glyph has a bit.
  bool
  text_at(const Png &png, const std::string &text, const int x0, const int y0)
  {
    for (int y = y0 - 1; y <= y0 + 8; ++y)
      for (int x = x0 - 1; x <= x0 + text_width(text); ++x)
        {
          if (x < 0 || y < 0 || x >= static_cast<int>(png.width) ||
              y >= static_cast<int>(png.height))
            return false;
          bool      ink = false;
          const int i = (x - x0) / 6, col = (x - x0) % 6, row = y - y0;
          if (x >= x0 && i < static_cast<int>(text.size()) && col < 5 && row >= 0 &&
              row < 8)
            ink = (glyphs[glyph_chars.find(text[i])][row] >> (4 - col)) & 1;
          if (dark(png.at(x, y)) != ink)
            return false;
        }
    return true;
  }

  // Whether `text` is drawn with its top-left corner within `radius` px of (x0, y0).
  bool
  text_near(const Png &png, const std::string &text, const int x0, const int y0)
  {
    constexpr int radius = 2;
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx)
        if (text_at(png, text, x0 + dx, y0 + dy))
          return true;
    return false;
  }

  // Pixel of an axis coordinate c in [lo, hi] on an axis from pixel p0 to p1.
  double
  pixel(const double c, const double lo, const double hi, const int p0, const int p1)
  {
    return p0 + (c - lo) / (hi - lo) * (p1 - p0);
  }

  // 8-connected clusters of pixels of exactly colour c inside the box: centroids sorted
  // by x.
  std::vector<std::array<double, 2>>
  clusters(const Png &png, const Color &c, const Box &box)
  {
    std::vector<std::array<double, 2>> result;
    std::vector<bool> seen(static_cast<std::size_t>(png.width) * png.height, false);
    for (int y = box.top + 1; y < box.bottom; ++y)
      for (int x = box.left + 1; x < box.right; ++x)
        if (png.at(x, y) == c && !seen[y * png.width + x])
          {
            double                          sx = 0, sy = 0;
            unsigned int                    n = 0;
            std::vector<std::array<int, 2>> stack{{{x, y}}};
            seen[y * png.width + x] = true;
            while (!stack.empty())
              {
                const auto [px, py] = stack.back();
                stack.pop_back();
                sx += px;
                sy += py;
                ++n;
                for (int dy = -1; dy <= 1; ++dy)
                  for (int dx = -1; dx <= 1; ++dx)
                    {
                      const int qx = px + dx, qy = py + dy;
                      if (qx > box.left && qx < box.right && qy > box.top &&
                          qy < box.bottom && png.at(qx, qy) == c &&
                          !seen[qy * png.width + qx])
                        {
                          seen[qy * png.width + qx] = true;
                          stack.push_back({{qx, qy}});
                        }
                    }
              }
            result.push_back({{sx / n, sy / n}});
          }
    std::sort(result.begin(), result.end());
    return result;
  }

  // Number of separate black runs along a row (horizontal) or a column from a to b.
  unsigned int
  black_runs(const Png &png, const bool along_row, const int at, const int a, const int b)
  {
    unsigned int runs = 0;
    bool         in   = false;
    for (int i = a; i <= b; ++i)
      {
        const bool black =
          (along_row ? png.at(i, at) : png.at(at, i)) == Color{{0, 0, 0}};
        runs += black && !in;
        in = black;
      }
    return runs;
  }

  // Light grey (grid) pixels in column x (or row y) strictly inside the box, as a
  // fraction of the box's inner height (or width).
  double
  grey_fraction(const Png &png, const Box &box, const bool column, const int at)
  {
    unsigned int n = 0, total = 0;
    for (int i = (column ? box.top : box.left) + 1; i < (column ? box.bottom : box.right);
         ++i)
      {
        const Color c = column ? png.at(at, i) : png.at(i, at);
        n += c[0] == c[1] && c[1] == c[2] && c[0] >= 200 && c[0] < 255;
        ++total;
      }
    return static_cast<double>(n) / total;
  }

  // Bounding box (width, height) of the pixels of exactly colour c in [x0, x1] x [y0,
  // y1].
  std::array<int, 2>
  extent(const Png   &png,
         const Color &c,
         const int    x0,
         const int    y0,
         const int    x1,
         const int    y1)
  {
    int left = x1 + 1, right = x0 - 1, top = y1 + 1, bottom = y0 - 1;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (png.at(x, y) == c)
          {
            left   = std::min(left, x);
            right  = std::max(right, x);
            top    = std::min(top, y);
            bottom = std::max(bottom, y);
          }
    return {{std::max(0, right - left + 1), std::max(0, bottom - top + 1)}};
  }
} // namespace


int
main(int argc, char **argv)
{
  ConditionalOStream out(std::cout);
  namespace fs       = std::filesystem;
  const double   nan = std::numeric_limits<double>::quiet_NaN();
  const fs::path directory =
    fs::temp_directory_path() / ("clothsim_line_plot_test_" + std::to_string(getpid()));
  fs::create_directories(directory);

  const Color red{{220, 30, 30}}, blue{{30, 60, 200}}, green{{20, 160, 60}},
    orange{{240, 140, 0}};
  const unsigned int width = 800, panel_height = 300;

  // Panel 1: two labelled curves, one dashed, over t in [0, 10]. Panel 2: y = x on
  // [0, 1] without a label (no legend over the line), to locate it in its box.
  PlotPanel  probes{"Probe 1: displacement z", "time (s)", "u_z (m)", {}};
  PlotSeries sine{"run A: sin(t)", {}, {}, red, false};
  PlotSeries cosine{"run B: 0.8 cos(t)", {}, {}, blue, true};
  for (unsigned int i = 0; i <= 400; ++i)
    {
      const double t = 10. * i / 400;
      sine.x.push_back(t);
      sine.y.push_back(std::sin(t));
      cosine.x.push_back(t);
      cosine.y.push_back(0.8 * std::cos(t));
    }
  probes.series = {sine, cosine};
  PlotPanel  diagonal{"y = x", "x", "y", {}};
  PlotSeries identity{"", {}, {}, green, false};
  for (unsigned int i = 0; i <= 100; ++i)
    {
      identity.x.push_back(i / 100.);
      identity.y.push_back(i / 100.);
    }
  diagonal.series = {identity};

  const std::string file = argc > 1 ? argv[1] : (directory / "two_panels.png").string();
  out << "two-panel plot " << file << std::endl;
  write_line_plot(file, {probes, diagonal}, width, panel_height);
  const Png png = read_png(file);
  check(out,
        true,
        "PNG read back: signature, chunk CRCs, IHDR 8-bit RGB, IDAT, filter 0");
  check_equal(out, "width", png.width, width);
  check_equal(out, "height", png.height, 2 * panel_height);
  check(out, png.at(0, 0) == Color{{255, 255, 255}}, "top-left corner pixel is white");
  check(out,
        png.at(width - 1, 2 * panel_height - 1) == Color{{255, 255, 255}},
        "bottom-right corner pixel is white");
  check_at_least(out, "pixels of series 'run A' (solid)", count_color(png, red), width);
  check_at_least(out,
                 "pixels of series 'run B' (dashed)",
                 count_color(png, blue),
                 width / 2);
  check_at_least(out, "pixels of series y = x", count_color(png, green), width / 2);

  const Box box1 = find_box(png, 0, panel_height);
  const Box box2 = find_box(png, panel_height, 2 * panel_height);
  check(out,
        box1.top > 0 && box1.bottom > box1.top + 100 && box1.right > box1.left + 400,
        "axes box found in panel 1");
  check(out,
        box2.top > 0 && box2.bottom > box2.top + 100 && box2.right > box2.left + 400,
        "axes box found in panel 2");
  check_at_least(out,
                 "dark pixels in the title area above box 1",
                 count_dark(png, 0, 0, width, box1.top),
                 50);
  check_at_least(out,
                 "dark pixels in the legend (top right of box 1)",
                 count_dark(png,
                            box1.left + (box1.right - box1.left) / 2,
                            box1.top + 2,
                            box1.right - 1,
                            box1.top + 40),
                 50);
  check_at_least(out,
                 "dark pixels in the tick labels below box 1",
                 count_dark(png, 0, box1.bottom + 6, width, box1.bottom + 20),
                 50);
  const auto centre = centroid(png, green);
  check_near(out,
             "y = x centroid x - box 2 centre x",
             centre[0] - 0.5 * (box2.left + box2.right),
             0,
             3);
  check_near(out,
             "y = x centroid y - box 2 centre y",
             centre[1] - 0.5 * (box2.top + box2.bottom),
             0,
             3);

  // Degenerate data: a constant series (sits mid-box), an all-NaN series, a series broken
  // by NaN, no series at all.
  PlotSeries constant{"constant", {0., 1., 2.}, {5., 5., 5.}, orange, false};
  PlotSeries all_nan{"all NaN", {nan, nan}, {nan, nan}, red, false};
  PlotSeries broken{"broken", {0., 1., 2., 3., 4.}, {0., 1., nan, 3., 4.}, blue, true};
  const std::string degenerate = (directory / "degenerate.png").string();
  write_line_plot(degenerate,
                  {PlotPanel{"constant and all-NaN", "x", "y", {constant, all_nan}},
                   PlotPanel{"only NaN", "", "", {all_nan}},
                   PlotPanel{"broken by NaN", "", "", {broken}},
                   PlotPanel{"no series", "", "", {}}},
                  400,
                  200);
  const Png small = read_png(degenerate);
  check(out,
        small.width == 400 && small.height == 800,
        "degenerate series: 400 x 800 written");
  const Box box = find_box(small, 0, 200);
  // The legend sample of 'constant' is orange as well: only count pixels left of it.
  double       sy = 0;
  unsigned int n  = 0;
  for (int y = box.top; y <= box.bottom; ++y)
    for (int x = box.left; x < (box.left + box.right) / 2; ++x)
      if (small.at(x, y) == orange)
        {
          sy += y;
          ++n;
        }
  check_at_least(out, "pixels of the constant series in the left half", n, 100);
  check_near(out,
             "constant series y - box centre y",
             sy / n - 0.5 * (box.top + box.bottom),
             0,
             1.5);

  // Log axes and markers. Panel 1: y = x^-2 at 13 points 0.25 decade apart over x in
  // [1e-3, 1], markers only, interleaved with points a log axis must skip (x = 0, x < 0,
  // y = 0, y < 0, NaN). In log space the 5% margin gives x in [-3.15, 0.15], y in
  // [-0.3, 6.3].
  const Color purple{{150, 40, 190}};
  PlotSeries  power{"", {}, {}, purple, false, true, false};
  for (unsigned int i = 0; i <= 12; ++i)
    {
      const double x = std::pow(10., -3. + 0.25 * i);
      power.x.push_back(x);
      power.y.push_back(1. / (x * x));
      if (i == 4)
        for (const auto &[bad_x, bad_y] : {std::array<double, 2>{{0., 5.}},
                                           {{-1., 1.}},
                                           {{1e-2, 0.}},
                                           {{1e-2, -3.}},
                                           {{nan, 1.}}})
          {
            power.x.push_back(bad_x);
            power.y.push_back(bad_y);
          }
    }
  PlotPanel log_log{"convergence: y = x^-2", "h", "error", {power}, true, true};

  // Panel 2: log ranges narrower than a decade, line and markers: x in [4.2, 6.5] (of 1,
  // 2, 5 x 10^k only 5 inside: ticks at 5 and 6), y in [2, 7] (ticks at 2 and 5).
  PlotSeries narrow_series{"", {4.2, 5., 6.5}, {2., 4., 7.}, orange, false, true, true};
  PlotPanel  narrow{"narrow log ranges", "x", "y", {narrow_series}, true, true};

  // Panel 3: linear x, log y. A line broken by y = -1 at x = 2, and legend samples of a
  // line, a scatter (markers, no line) and a line with markers; their data stay in the
  // bottom-left, away from the legend.
  PlotSeries falling{"line", {0., 1., 2., 3., 4.}, {1e3, 1e2, -1., 10., 1.}, red, false};
  PlotSeries scatter{"scatter", {0.2, 0.4, 0.6}, {2., 3., 2.}, blue, false, true, false};
  PlotSeries both{"line+markers", {0.2, 0.6}, {1.5, 1.5}, green, false, true, true};
  PlotPanel  mixed{"broken by y <= 0", "x", "y", {falling, scatter, both}, false, true};

  // Panel 4: nothing positive on either log axis.
  PlotSeries nothing{"nothing", {0., -1., 2.}, {1., 2., -3.}, blue, false, true, false};
  PlotPanel  empty_log{"no positive data", "", "", {nothing}, true, true};

  // Panel 5: log y in [1.1, 1.8], no 1..9 x 10^k inside: linear ticks 1.2, ..., 1.8.
  PlotSeries slim_series{"", {0., 1.}, {1.1, 1.8}, green, false};
  PlotPanel  slim{"factor 1.6", "", "", {slim_series}, false, true};

  const std::string log_file = argc > 2 ? argv[2] : (directory / "log_axes.png").string();
  out << "log plot " << log_file << std::endl;
  bool written = false;
  try
    {
      write_line_plot(log_file,
                      {log_log, narrow, mixed, empty_log, slim},
                      width,
                      panel_height);
      written = true;
    }
  catch (const std::exception &e)
    {
      out << "  write_line_plot threw: " << e.what() << std::endl;
    }
  check(out, written, "log plot with non-positive values written without throwing");
  const Png logs = written ? read_png(log_file) : Png{};
  check(out,
        logs.width == width && logs.height == 5 * panel_height,
        "log plot: 800 x 1500");
  if (logs.width == width && logs.height == 5 * panel_height)
    {
      // Panel 1: every marker a separate cluster at its log-log position.
      const Box lb = find_box(logs, 0, panel_height);
      check(out,
            lb.top > 0 && lb.bottom > lb.top + 100 && lb.right > lb.left + 400,
            "axes box found in the log-log panel");
      const auto markers = clusters(logs, purple, lb);
      check_equal(out,
                  "separate marker clusters of y = x^-2 (13 points, no line)",
                  markers.size(),
                  std::size_t(13));
      if (markers.size() == 13)
        {
          double worst_x = 0, worst_y = 0, worst_dx = 0, worst_dy = 0;
          for (unsigned int i = 0; i <= 12; ++i)
            {
              const double lx = -3. + 0.25 * i, ly = -2. * lx;
              // A marker is centred on (pixel + 0.5, pixel + 0.5).
              worst_x = std::max(worst_x,
                                 std::abs(markers[i][0] - 0.5 -
                                          pixel(lx, -3.15, 0.15, lb.left, lb.right)));
              worst_y = std::max(worst_y,
                                 std::abs(markers[i][1] - 0.5 -
                                          pixel(ly, -0.3, 6.3, lb.bottom, lb.top)));
            }
          const double gap_x = (markers[12][0] - markers[0][0]) / 12,
                       gap_y = (markers[12][1] - markers[0][1]) / 12;
          for (unsigned int i = 0; i < 12; ++i)
            {
              worst_dx =
                std::max(worst_dx, std::abs(markers[i + 1][0] - markers[i][0] - gap_x));
              worst_dy =
                std::max(worst_dy, std::abs(markers[i + 1][1] - markers[i][1] - gap_y));
            }
          check_near(out, "largest |marker x - log-space position| (px)", worst_x, 0, 1);
          check_near(out, "largest |marker y - log-space position| (px)", worst_y, 0, 1);
          check_near(out, "largest deviation from equal x spacing (px)", worst_dx, 0, 1);
          check_near(out, "largest deviation from equal y spacing (px)", worst_dy, 0, 1);
          check_near(out,
                     "y spacing / x spacing of the markers",
                     gap_y / gap_x,
                     2. * (lb.bottom - lb.top) / 6.6 / ((lb.right - lb.left) / 3.3),
                     0.02);
          unsigned int between = 0;
          for (unsigned int i = 0; i < 12; ++i)
            {
              const int mx = std::lround(0.5 * (markers[i][0] + markers[i + 1][0]));
              const int my = std::lround(0.5 * (markers[i][1] + markers[i + 1][1]));
              for (int y = my - 3; y <= my + 3; ++y)
                for (int x = mx - 3; x <= mx + 3; ++x)
                  between += logs.at(x, y) == purple;
            }
          check_equal(out,
                      "series pixels midway between neighbouring markers",
                      between,
                      0u);
        }
      check(out,
            count_color(logs, purple) <= 13 * 49,
            "series pixels of y = x^-2 fit in 13 markers of at most 7 x 7 px");

      // Decade ticks and their labels, read back pixel by pixel.
      bool x_ticks = true, x_labels = true;
      for (int k = -3; k <= 0; ++k)
        {
          const int         x     = std::lround(pixel(k, -3.15, 0.15, lb.left, lb.right));
          const std::string label = "1e" + std::to_string(k);
          x_ticks = x_ticks && black_runs(logs, true, lb.bottom + 3, x - 1, x + 1) == 1;
          x_labels =
            x_labels && text_near(logs, label, x - text_width(label) / 2, lb.bottom + 9);
        }
      check(out, x_ticks, "x tick marks at 1e-3, 1e-2, 1e-1, 1e0");
      check(out,
            x_labels,
            "x tick labels '1e-3', '1e-2', '1e-1', '1e0' under their ticks");
      bool y_labels = true;
      for (int k = 0; k <= 6; ++k)
        {
          const int         y     = std::lround(pixel(k, -0.3, 6.3, lb.bottom, lb.top));
          const std::string label = "1e" + std::to_string(k);
          y_labels =
            y_labels && text_near(logs, label, lb.left - 9 - text_width(label), y - 3);
        }
      check(out, y_labels, "y tick labels '1e0' ... '1e6' left of their ticks");
      check_equal(out,
                  "x tick marks under the log-log box (4 decades)",
                  black_runs(logs, true, lb.bottom + 3, lb.left - 2, lb.right + 2),
                  4u);
      check(out,
            !text_near(logs,
                       "0.01",
                       std::lround(pixel(-2, -3.15, 0.15, lb.left, lb.right)) - 11,
                       lb.bottom + 9),
            "no fixed-point label '0.01'");

      // Minor grid: x lines at 2..9 x 10^k (about 210 px per decade), none between 1 and
      // 2 x 10^k; y decades are 36 px apart, too dense for minor lines.
      double minor_x = 1;
      for (const double m : {2., 3., 5., 9.})
        {
          const int x =
            std::lround(pixel(std::log10(m * 1e-2), -3.15, 0.15, lb.left, lb.right));
          minor_x = std::min(minor_x,
                             std::max({grey_fraction(logs, lb, true, x - 1),
                                       grey_fraction(logs, lb, true, x),
                                       grey_fraction(logs, lb, true, x + 1)}));
        }
      check_at_least(out,
                     "grid fraction of the minor x lines at 2, 3, 5, 9 x 1e-2",
                     minor_x,
                     0.9);
      const int x15 =
        std::lround(pixel(std::log10(1.5e-2), -3.15, 0.15, lb.left, lb.right));
      check(out,
            grey_fraction(logs, lb, true, x15) < 0.2,
            "no grid line at 1.5e-2 (between two minor lines)");
      const int y200 = std::lround(pixel(std::log10(200.), -0.3, 6.3, lb.bottom, lb.top));
      check(out,
            grey_fraction(logs, lb, false, y200) < 0.3,
            "no minor y grid line at 200 (decades too close)");

      // Panel 2: two labelled ticks on each narrow log axis: x at 5 and 6, y at 2 and 5.
      // Range of data in [a, b] on a log axis, margin included.
      const auto log_range = [](const double a, const double b) {
        const double span = std::log10(b / a);
        return std::array<double, 2>{
          {std::log10(a) - 0.05 * span, std::log10(b) + 0.05 * span}};
      };
      const Box nb = find_box(logs, panel_height, 2 * panel_height);
      check(out,
            nb.top > 0 && nb.right > nb.left + 400,
            "axes box found in the narrow panel");
      check_equal(out,
                  "x tick marks of the narrow log x axis [4.2, 6.5]",
                  black_runs(logs, true, nb.bottom + 3, nb.left - 2, nb.right + 2),
                  2u);
      check_equal(out,
                  "y tick marks of the narrow log y axis [2, 7]",
                  black_runs(logs, false, nb.left - 3, nb.top - 2, nb.bottom + 2),
                  2u);
      const auto nx = log_range(4.2, 6.5), ny = log_range(2., 7.);
      bool       five_six = true, two_five = true;
      for (const int m : {5, 6})
        {
          const int x =
            std::lround(pixel(std::log10(m), nx[0], nx[1], nb.left, nb.right));
          const std::string label = std::to_string(m) + "e0";
          five_six = five_six && text_near(logs, label, x - 8, nb.bottom + 9);
        }
      check(out, five_six, "narrow log x axis labels '5e0' and '6e0'");
      for (const int m : {2, 5})
        {
          const int y =
            std::lround(pixel(std::log10(m), ny[0], ny[1], nb.bottom, nb.top));
          const std::string label = std::to_string(m) + "e0";
          two_five =
            two_five && text_near(logs, label, nb.left - 9 - text_width(label), y - 3);
        }
      check(out, two_five, "narrow log y axis labels '2e0' and '5e0'");
      check_equal(out,
                  "marker clusters of the narrow line+markers series (line joins them)",
                  clusters(logs, orange, nb).size(),
                  std::size_t(1));

      // Panel 3: the line breaks at the non-positive value; legend samples.
      const Box mb = find_box(logs, 2 * panel_height, 3 * panel_height);
      check(out,
            mb.top > 0 && mb.right > mb.left + 400,
            "axes box found in the mixed panel");
      const int x2 = std::lround(pixel(2., -0.2, 4.2, mb.left, mb.right));
      check_equal(out,
                  "line pixels at x = 2, where y = -1 breaks the line",
                  extent(logs, red, x2 - 3, mb.top + 1, x2 + 3, mb.bottom - 1)[1],
                  0);
      const int x1 = std::lround(pixel(1., -0.2, 4.2, mb.left, mb.right));
      check_at_least(out,
                     "line pixels at x = 1 (before the break)",
                     extent(logs, red, x1 - 3, mb.top + 1, x1 + 3, mb.bottom - 1)[1],
                     1);
      const int  middle = (mb.left + mb.right) / 2;
      const auto legend = [&](const Color &c) {
        return extent(logs, c, middle, mb.top + 1, mb.right - 1, mb.top + 50);
      };
      const auto line_sample = legend(red), scatter_sample = legend(blue),
                 both_sample = legend(green);
      check(out,
            line_sample[0] >= 20 && line_sample[1] <= 2,
            "legend of the line series: a line sample, 2 px high");
      check(out,
            scatter_sample[0] >= 5 && scatter_sample[0] <= 7 && scatter_sample[1] >= 5 &&
              scatter_sample[1] <= 7,
            "legend of the scatter series: a marker only, about 6 x 6 px");
      check(out,
            both_sample[0] >= 20 && both_sample[1] >= 5 && both_sample[1] <= 7,
            "legend of the line+markers series: a line sample with a marker");
      check_equal(
        out,
        "scatter markers in the mixed panel (3 points, no line)",
        clusters(logs, blue, Box{mb.left, middle, mb.top + 60, mb.bottom}).size(),
        std::size_t(3));

      // Panel 4: no positive data: an empty box with default decade ticks.
      const Box eb = find_box(logs, 3 * panel_height, 4 * panel_height);
      check(out,
            eb.top > 0 && eb.right > eb.left + 400 &&
              black_runs(logs, true, eb.bottom + 3, eb.left - 2, eb.right + 2) >= 2,
            "panel without positive data: box and at least two ticks");

      // Panel 5: linear ticks on a log axis less than a factor 2 wide.
      const Box  sb = find_box(logs, 4 * panel_height, 5 * panel_height);
      const auto sy = log_range(1.1, 1.8);
      check_equal(out,
                  "y tick marks of the log y axis [1.1, 1.8]",
                  black_runs(logs, false, sb.left - 3, sb.top - 2, sb.bottom + 2),
                  4u);
      bool linear_labels = true;
      for (const std::string label : {"1.2", "1.4", "1.6", "1.8"})
        {
          const int y = std::lround(
            pixel(std::log10(std::stod(label)), sy[0], sy[1], sb.bottom, sb.top));
          linear_labels = linear_labels &&
                          text_near(logs, label, sb.left - 9 - text_width(label), y - 3);
        }
      check(out,
            linear_labels,
            "log y axis [1.1, 1.8] labels '1.2', '1.4', '1.6', '1.8'");
    }

  // A path that cannot be written.
  const std::string bad = (directory / "no-such-directory" / "plot.png").string();
  try
    {
      write_line_plot(bad, {probes});
      check(out, false, "writing into a missing directory throws");
    }
  catch (const std::runtime_error &e)
    {
      check(out,
            std::string(e.what()).find(bad) != std::string::npos,
            std::string("writing into a missing directory throws: ") + e.what());
    }

  fs::remove_all(directory);
  return finish_tally(out);
}
