#pragma once

// The parts of io/line_plot shared by its files: the RGB raster, text in the bitmap font
// (io/line_plot_font.cc), axis scales and ticks (io/line_plot_axes.cc), the PNG encoder
// (io/line_plot_png.cc). Not part of the interface.

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace clothsim::io::detail
{
  using Color = std::array<unsigned char, 3>;

  // Rows of a glyph of the bitmap font (the last one only for descenders); glyphs are 5
  // columns wide.
  constexpr int glyph_rows = 8;


  // RGB raster, white to start with. Pixels outside the clip rectangle are ignored.
  struct Image
  {
    Image(const int width, const int height)
      : width(width)
      , height(height)
      , pixels(3 * static_cast<std::size_t>(width) * height, 255)
    {
      reset_clip();
    }

    void
    set(const int x, const int y, const Color &c)
    {
      if (x < clip_x0 || x > clip_x1 || y < clip_y0 || y > clip_y1)
        return;
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
      pixels[i]           = c[0];
      pixels[i + 1]       = c[1];
      pixels[i + 2]       = c[2];
    }

    void
    fill(const int x0, const int y0, const int x1, const int y1, const Color &c)
    {
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          set(x, y, c);
    }

    void
    clip(const int x0, const int y0, const int x1, const int y1)
    {
      clip_x0 = std::max(x0, 0);
      clip_y0 = std::max(y0, 0);
      clip_x1 = std::min(x1, width - 1);
      clip_y1 = std::min(y1, height - 1);
    }

    void
    reset_clip()
    {
      clip(0, 0, width - 1, height - 1);
    }

    int                        width, height;
    std::vector<unsigned char> pixels;
    int                        clip_x0, clip_y0, clip_x1, clip_y1;
  };


  // Width in pixels of the text in the bitmap font.
  int
  text_width(const std::string &text);

  // The text, cut short with ".." if it is wider than `room` pixels.
  std::string
  fit_text(const std::string &text, const int room);

  // Text with its top-left corner at (x, y). Vertical text reads bottom to top, with
  // (x, y) the bottom-left corner. Bold doubles every column.
  void
  draw_text(Image             &image,
            const std::string &text,
            const int          x,
            const int          y,
            const Color       &c,
            const bool         bold     = false,
            const bool         vertical = false);


  // An axis as drawn, in axis coordinates: the value on a linear axis, its log10 on a
  // log axis. Range [lo, hi], labelled ticks, and unlabelled minor grid lines.
  struct Scale
  {
    bool                     log = false;
    double                   lo = 0., hi = 1.;
    std::vector<double>      major;
    std::vector<std::string> labels; // one per major tick
    std::vector<double>      minor;
  };

  // Linear axis for data in [vmin, vmax] (vmin > vmax: no data): 5% margin, 4-6 ticks
  // at a 1, 2 or 5 x 10^k step.
  Scale
  make_linear_scale(const double vmin, const double vmax);

  // Log axis for data with log10 in [lmin, lmax] (lmin > lmax: no data): 5% margin in
  // log space; labelled ticks at the decades (every 2nd, 5th, 10th, ... if there are
  // more than 8), else at 1, 2, 5 x 10^k, else at 1..9 x 10^k, else at a linear step,
  // whichever first gives at least two.
  Scale
  make_log_scale(double lmin, double lmax);

  // Whether the grid lines, minor ones included, are at least 3 px apart on an axis
  // `pixels` long.
  bool
  minor_grid_fits(const Scale &scale, const int pixels);

  // Pixel of an axis coordinate on an axis running from pixel p0 (at lo) to p1 (at hi).
  int
  to_pixel(const double value, const Scale &scale, const int p0, const int p1);


  // The image as an 8-bit RGB PNG file's bytes.
  std::string
  encode_png(const Image &image);
} // namespace clothsim::io::detail
