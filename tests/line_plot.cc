// Unit test of clothsim::io::write_line_plot: writes plots of known series, reads the PNG
// back (chunk CRCs, IHDR, inflated IDAT, filter bytes) and checks size, background,
// series colours, text, the position of y = x in its box, degenerate series and a bad
// path. With an argument, the two-panel plot is kept at that path.

#include "io/line_plot.h"

#include <unistd.h>
#include <zlib.h>

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

namespace
{
  unsigned int n_checks   = 0;
  unsigned int n_failures = 0;

  void
  check(const bool ok, const std::string &what)
  {
    ++n_checks;
    if (!ok)
      ++n_failures;
    std::cout << (ok ? "  ok    " : "  FAIL  ") << what << std::endl;
  }

  template <typename T>
  void
  check_equal(const std::string &what, const T &value, const T &expected)
  {
    std::ostringstream text;
    text << what << " = " << value << " (expected " << expected << ")";
    check(value == expected, text.str());
  }

  void
  check_at_least(const std::string &what, const double value, const double minimum)
  {
    std::ostringstream text;
    text << what << " = " << value << " (expected >= " << minimum << ")";
    check(value >= minimum, text.str());
  }

  void
  check_near(const std::string &what,
             const double       value,
             const double       expected,
             const double       tolerance)
  {
    std::ostringstream text;
    text << what << " = " << value << " (expected " << expected << " +- " << tolerance
         << ")";
    check(std::abs(value - expected) <= tolerance, text.str());
  }

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
} // namespace


int
main(int argc, char **argv)
{
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
  std::cout << "two-panel plot " << file << std::endl;
  write_line_plot(file, {probes, diagonal}, width, panel_height);
  const Png png = read_png(file);
  check(true, "PNG read back: signature, chunk CRCs, IHDR 8-bit RGB, IDAT, filter 0");
  check_equal("width", png.width, width);
  check_equal("height", png.height, 2 * panel_height);
  check(png.at(0, 0) == Color{{255, 255, 255}}, "top-left corner pixel is white");
  check(png.at(width - 1, 2 * panel_height - 1) == Color{{255, 255, 255}},
        "bottom-right corner pixel is white");
  check_at_least("pixels of series 'run A' (solid)", count_color(png, red), width);
  check_at_least("pixels of series 'run B' (dashed)", count_color(png, blue), width / 2);
  check_at_least("pixels of series y = x", count_color(png, green), width / 2);

  const Box box1 = find_box(png, 0, panel_height);
  const Box box2 = find_box(png, panel_height, 2 * panel_height);
  check(box1.top > 0 && box1.bottom > box1.top + 100 && box1.right > box1.left + 400,
        "axes box found in panel 1");
  check(box2.top > 0 && box2.bottom > box2.top + 100 && box2.right > box2.left + 400,
        "axes box found in panel 2");
  check_at_least("dark pixels in the title area above box 1",
                 count_dark(png, 0, 0, width, box1.top),
                 50);
  check_at_least("dark pixels in the legend (top right of box 1)",
                 count_dark(png,
                            box1.left + (box1.right - box1.left) / 2,
                            box1.top + 2,
                            box1.right - 1,
                            box1.top + 40),
                 50);
  check_at_least("dark pixels in the tick labels below box 1",
                 count_dark(png, 0, box1.bottom + 6, width, box1.bottom + 20),
                 50);
  const auto centre = centroid(png, green);
  check_near("y = x centroid x - box 2 centre x",
             centre[0] - 0.5 * (box2.left + box2.right),
             0,
             3);
  check_near("y = x centroid y - box 2 centre y",
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
  check(small.width == 400 && small.height == 800,
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
  check_at_least("pixels of the constant series in the left half", n, 100);
  check_near("constant series y - box centre y",
             sy / n - 0.5 * (box.top + box.bottom),
             0,
             1.5);

  // A path that cannot be written.
  const std::string bad = (directory / "no-such-directory" / "plot.png").string();
  try
    {
      write_line_plot(bad, {probes});
      check(false, "writing into a missing directory throws");
    }
  catch (const std::runtime_error &e)
    {
      check(std::string(e.what()).find(bad) != std::string::npos,
            std::string("writing into a missing directory throws: ") + e.what());
    }

  fs::remove_all(directory);
  std::cout << n_checks - n_failures << " of " << n_checks << " checks passed"
            << std::endl;
  return n_failures == 0 ? 0 : 1;
}
