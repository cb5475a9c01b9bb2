// Line plots drawn into an RGB buffer (Bresenham lines, disc markers, a 5x7 bitmap font
// with descenders) on linear or log10 axes, written as an 8-bit RGB PNG: signature, IHDR,
// one zlib-compressed IDAT with filter type 0 on every row, IEND.

#include "io/line_plot.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace clothsim::io
{
  namespace
  {
    using Color = std::array<unsigned char, 3>;

    constexpr Color black{{0, 0, 0}};
    constexpr Color white{{255, 255, 255}};
    constexpr Color grid_grey{{225, 225, 225}};
    constexpr Color minor_grey{{240, 240, 240}}; // minor grid of log axes

    // Font for ASCII 32..126: 8 rows per glyph (row 7 only for descenders), one byte per
    // row, bit 4 the leftmost of 5 columns. Text advances 6 px per character.
    constexpr int           glyph_rows           = 8;
    constexpr int           char_advance         = 6;
    constexpr unsigned char font[95][glyph_rows] = {
      {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, // ' '
      {0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04, 0x00}, // !
      {0x0A, 0x0A, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x00}, // "
      {0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A, 0x00}, // #
      {0x04, 0x0F, 0x14, 0x0E, 0x05, 0x1E, 0x04, 0x00}, // $
      {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03, 0x00}, // %
      {0x0C, 0x12, 0x14, 0x08, 0x15, 0x12, 0x0D, 0x00}, // &
      {0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00, 0x00}, // '
      {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02, 0x00}, // (
      {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08, 0x00}, // )
      {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00, 0x00}, // *
      {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00, 0x00}, // +
      {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}, // ,
      {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00, 0x00}, // -
      {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C, 0x00}, // .
      {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00, 0x00}, // /
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
      {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00, 0x00}, // :
      {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x04, 0x08}, // ;
      {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02, 0x00}, // <
      {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00, 0x00}, // =
      {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08, 0x00}, // >
      {0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04, 0x00}, // ?
      {0x0E, 0x11, 0x01, 0x0D, 0x15, 0x15, 0x0E, 0x00}, // @
      {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x00}, // A
      {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E, 0x00}, // B
      {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E, 0x00}, // C
      {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C, 0x00}, // D
      {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F, 0x00}, // E
      {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10, 0x00}, // F
      {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F, 0x00}, // G
      {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11, 0x00}, // H
      {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E, 0x00}, // I
      {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C, 0x00}, // J
      {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11, 0x00}, // K
      {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F, 0x00}, // L
      {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11, 0x00}, // M
      {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x00}, // N
      {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E, 0x00}, // O
      {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10, 0x00}, // P
      {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D, 0x00}, // Q
      {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11, 0x00}, // R
      {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E, 0x00}, // S
      {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x00}, // T
      {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E, 0x00}, // U
      {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04, 0x00}, // V
      {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A, 0x00}, // W
      {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11, 0x00}, // X
      {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x00}, // Y
      {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F, 0x00}, // Z
      {0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E, 0x00}, // [
      {0x00, 0x10, 0x08, 0x04, 0x02, 0x01, 0x00, 0x00}, // backslash
      {0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E, 0x00}, // ]
      {0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00, 0x00}, // ^
      {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F, 0x00}, // _
      {0x08, 0x04, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00}, // `
      {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F, 0x00}, // a
      {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E, 0x00}, // b
      {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E, 0x00}, // c
      {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F, 0x00}, // d
      {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E, 0x00}, // e
      {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08, 0x00}, // f
      {0x00, 0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}, // g
      {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11, 0x00}, // h
      {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E, 0x00}, // i
      {0x02, 0x00, 0x06, 0x02, 0x02, 0x02, 0x12, 0x0C}, // j
      {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12, 0x00}, // k
      {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E, 0x00}, // l
      {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11, 0x00}, // m
      {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11, 0x00}, // n
      {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E, 0x00}, // o
      {0x00, 0x00, 0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10}, // p
      {0x00, 0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x01}, // q
      {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10, 0x00}, // r
      {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E, 0x00}, // s
      {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06, 0x00}, // t
      {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D, 0x00}, // u
      {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04, 0x00}, // v
      {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A, 0x00}, // w
      {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x00}, // x
      {0x00, 0x00, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}, // y
      {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F, 0x00}, // z
      {0x02, 0x04, 0x04, 0x08, 0x04, 0x04, 0x02, 0x00}, // {
      {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x00}, // |
      {0x08, 0x04, 0x04, 0x02, 0x04, 0x04, 0x08, 0x00}, // }
      {0x00, 0x00, 0x08, 0x15, 0x02, 0x00, 0x00, 0x00}, // ~
    };


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


    int
    text_width(const std::string &text)
    {
      return text.empty() ? 0 : char_advance * static_cast<int>(text.size()) - 1;
    }

    // The text, cut short with ".." if it is wider than `room` pixels.
    std::string
    fit_text(const std::string &text, const int room)
    {
      if (text_width(text) <= room)
        return text;
      const int n = std::max(0, (room + 1) / char_advance - 2);
      return text.substr(0, n) + "..";
    }

    // Text with its top-left corner at (x, y). Vertical text reads bottom to top, with
    // (x, y) the bottom-left corner. Bold doubles every column.
    void
    draw_text(Image             &image,
              const std::string &text,
              const int          x,
              const int          y,
              const Color       &c,
              const bool         bold     = false,
              const bool         vertical = false)
    {
      for (std::size_t i = 0; i < text.size(); ++i)
        {
          const unsigned char ch    = text[i];
          const auto         &glyph = font[(ch >= 32 && ch <= 126 ? ch : '?') - 32];
          for (int row = 0; row < glyph_rows; ++row)
            for (int col = 0; col < 5; ++col)
              if ((glyph[row] >> (4 - col)) & 1)
                for (int b = 0; b <= (bold ? 1 : 0); ++b)
                  {
                    const int along = char_advance * static_cast<int>(i) + col + b;
                    if (vertical)
                      image.set(x + row, y - along, c);
                    else
                      image.set(x + along, y + row, c);
                  }
        }
    }

    // 2x2 dot: data lines are 2 px wide.
    void
    dot(Image &image, const int x, const int y, const Color &c)
    {
      image.fill(x, y, x + 1, y + 1, c);
    }

    // Filled disc, 6 px across with the corners cut, centred like dot() on (x + 0.5,
    // y + 0.5) so that it sits on a line through (x, y).
    void
    marker(Image &image, const int x, const int y, const Color &c)
    {
      for (int dy = -2; dy <= 3; ++dy)
        for (int dx = -2; dx <= 3; ++dx)
          if ((dx - 0.5) * (dx - 0.5) + (dy - 0.5) * (dy - 0.5) <= 8.5)
            image.set(x + dx, y + dy, c);
    }

    // Bresenham line of dots. `dash` (null: solid) counts dots along a series so that
    // dashes (10 on, 6 off) continue across segments.
    void
    draw_line(Image       &image,
              int          x0,
              int          y0,
              const int    x1,
              const int    y1,
              const Color &c,
              int         *dash)
    {
      const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
      const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
      int       err = dx + dy;
      while (true)
        {
          if (dash == nullptr || (*dash)++ % 16 < 10)
            dot(image, x0, y0, c);
          if (x0 == x1 && y0 == y1)
            break;
          const int e2 = 2 * err;
          if (e2 >= dy)
            {
              err += dy;
              x0 += sx;
            }
          if (e2 <= dx)
            {
              err += dx;
              y0 += sy;
            }
        }
    }


    // Axis range [lo, hi] with ticks at i * step, i = first..last.
    struct Axis
    {
      double    lo, hi, step;
      long long first, last;
    };

    // Range of the data [vmin, vmax] (vmin > vmax: no data) with a 5% margin, and 4-6
    // ticks at a 1, 2 or 5 x 10^k step.
    Axis
    make_axis(double vmin, double vmax)
    {
      if (!(vmin <= vmax))
        {
          vmin = 0.;
          vmax = 1.;
        }
      vmin = std::clamp(vmin, -1e300, 1e300);
      vmax = std::clamp(vmax, -1e300, 1e300);
      // A range lost in round-off counts as constant and gets a width of its own: 1, 2
      // or 5 x 10^k on either side, about 10% of the value.
      if (vmax - vmin <= 1e-9 * std::max(std::abs(vmin), std::abs(vmax)))
        {
          const double mid  = 0.5 * (vmin + vmax);
          double       half = 1.;
          if (mid != 0.)
            {
              const double target = 0.1 * std::abs(mid);
              half                = std::pow(10., std::floor(std::log10(target)));
              if (target >= 5. * half)
                half *= 5.;
              else if (target >= 2. * half)
                half *= 2.;
            }
          vmin = mid - half;
          vmax = mid + half;
        }
      Axis         axis;
      const double margin = 0.05 * (vmax - vmin);
      axis.lo             = vmin - margin;
      axis.hi             = vmax + margin;

      // Ticks inside the range can number 7 for one step and 2-3 for the next larger:
      // then widen the range to the next tick on the nearer side until there are 4.
      const auto count_ticks = [&axis](const double step) {
        axis.step  = step;
        axis.first = static_cast<long long>(std::ceil(axis.lo / step - 1e-9));
        axis.last  = static_cast<long long>(std::floor(axis.hi / step + 1e-9));
        return axis.last - axis.first + 1;
      };
      double decade = std::pow(10., std::floor(std::log10((axis.hi - axis.lo) / 10.)));
      const double factors[3] = {1., 2., 5.};
      for (unsigned int k = 0;; ++k)
        {
          const long long n = count_ticks(factors[k % 3] * decade);
          if (n <= 6)
            {
              while (axis.last - axis.first < 3)
                {
                  const double below = static_cast<double>(axis.first - 1) * axis.step;
                  const double above = static_cast<double>(axis.last + 1) * axis.step;
                  if (axis.lo - below <= above - axis.hi)
                    {
                      axis.lo = std::min(axis.lo, below);
                      --axis.first;
                    }
                  else
                    {
                      axis.hi = std::max(axis.hi, above);
                      ++axis.last;
                    }
                }
              break;
            }
          if (k % 3 == 2)
            decade *= 10.;
        }
      return axis;
    }

    // Shortest labels that tell the ticks apart: fixed point ("0.25") for moderate
    // magnitudes, else scientific without padding ("1.5e4", "-1e-3").
    std::vector<std::string>
    tick_labels(const Axis &axis)
    {
      std::vector<double> values;
      for (long long i = axis.first; i <= axis.last; ++i)
        values.push_back(static_cast<double>(i) * axis.step);
      const double largest = std::max(std::abs(values.front()), std::abs(values.back()));
      const bool   scientific = largest >= 1e5 || largest < 1e-3;

      std::vector<std::string> labels(values.size());
      char                     buffer[64];
      if (!scientific)
        {
          const int decimals =
            std::max(0, -static_cast<int>(std::floor(std::log10(axis.step) + 1e-9)));
          for (std::size_t i = 0; i < values.size(); ++i)
            {
              std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, values[i]);
              std::string text = buffer;
              if (text.find('.') != std::string::npos)
                {
                  text.erase(text.find_last_not_of('0') + 1);
                  if (text.back() == '.')
                    text.pop_back();
                }
              labels[i] = text;
            }
        }
      else
        for (int precision = 0; precision <= 16; ++precision)
          {
            bool exact = true;
            for (std::size_t i = 0; i < values.size(); ++i)
              {
                std::snprintf(buffer, sizeof(buffer), "%.*e", precision, values[i]);
                exact = exact && std::abs(std::strtod(buffer, nullptr) - values[i]) <=
                                   1e-3 * axis.step;
                // Compact: no trailing zeros in the mantissa, no padding in the exponent.
                std::string       text     = buffer;
                const std::size_t e        = text.find('e');
                std::string       mantissa = text.substr(0, e);
                if (mantissa.find('.') != std::string::npos)
                  {
                    mantissa.erase(mantissa.find_last_not_of('0') + 1);
                    if (mantissa.back() == '.')
                      mantissa.pop_back();
                  }
                labels[i] =
                  mantissa + "e" + std::to_string(std::atoi(text.c_str() + e + 1));
              }
            if (exact)
              break;
          }
      for (std::size_t i = 0; i < values.size(); ++i)
        if (axis.first + static_cast<long long>(i) == 0)
          labels[i] = "0";
      return labels;
    }


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

    Scale
    make_linear_scale(const double vmin, const double vmax)
    {
      const Axis axis = make_axis(vmin, vmax);
      Scale      scale;
      scale.lo = axis.lo;
      scale.hi = axis.hi;
      for (long long i = axis.first; i <= axis.last; ++i)
        scale.major.push_back(static_cast<double>(i) * axis.step);
      scale.labels = tick_labels(axis);
      return scale;
    }

    // Log axis for data with log10 in [lmin, lmax] (lmin > lmax: no data): 5% margin in
    // log space; labelled ticks at the decades (every 2nd, 5th, 10th, ... if there are
    // more than 8), else at 1, 2, 5 x 10^k, else at 1..9 x 10^k, else at a linear step,
    // whichever first gives at least two.
    Scale
    make_log_scale(double lmin, double lmax)
    {
      if (!(lmin <= lmax))
        {
          lmin = 0.;
          lmax = 1.;
        }
      lmin = std::clamp(lmin, -300., 300.);
      lmax = std::clamp(lmax, -300., 300.);
      if (lmax - lmin <= 1e-9) // constant: a factor 2 on either side
        {
          const double mid = 0.5 * (lmin + lmax);
          lmin             = mid - std::log10(2.);
          lmax             = mid + std::log10(2.);
        }
      Scale scale;
      scale.log           = true;
      const double margin = 0.05 * (lmax - lmin);
      scale.lo            = lmin - margin;
      scale.hi            = lmax + margin;

      constexpr double eps   = 1e-9;
      const auto       label = [](const int mantissa, const long long exponent) {
        return std::to_string(mantissa) + "e" + std::to_string(exponent);
      };
      const auto inside = [&](const double c) {
        return c >= scale.lo - eps && c <= scale.hi + eps;
      };
      const long long k0 = static_cast<long long>(std::ceil(scale.lo - eps));
      const long long k1 = static_cast<long long>(std::floor(scale.hi + eps));
      if (k1 - k0 + 1 >= 2)
        {
          // Decades; every step-th one if there are too many to label.
          long long step = 1, first = k0, last = k1;
          for (long long base = 1;; base *= 10)
            {
              bool found = false;
              for (const long long factor : {1, 2, 5})
                {
                  step  = factor * base;
                  first = static_cast<long long>(std::ceil(double(k0) / step));
                  last  = static_cast<long long>(std::floor(double(k1) / step));
                  if (last - first + 1 <= 8)
                    {
                      found = true;
                      break;
                    }
                }
              if (found)
                break;
            }
          for (long long i = first; i <= last; ++i)
            {
              scale.major.push_back(static_cast<double>(i * step));
              scale.labels.push_back(label(1, i * step));
            }
          if (step == 1)
            {
              for (long long k = k0 - 1; k <= k1; ++k)
                for (int m = 2; m <= 9; ++m)
                  if (inside(k + std::log10(m)))
                    scale.minor.push_back(k + std::log10(m));
            }
          else
            for (long long k = k0; k <= k1; ++k)
              if (k % step != 0)
                scale.minor.push_back(static_cast<double>(k));
          return scale;
        }

      // Less than two decades inside: label multiples of the decade.
      const std::vector<int> sets[2] = {{1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}};
      for (const std::vector<int> &mantissas : sets)
        {
          Scale candidate = scale;
          for (long long k = k0 - 1; k <= k1; ++k)
            for (int m = 1; m <= 9; ++m)
              {
                const double c = k + std::log10(m);
                if (!inside(c))
                  continue;
                if (std::find(mantissas.begin(), mantissas.end(), m) != mantissas.end())
                  {
                    candidate.major.push_back(c);
                    candidate.labels.push_back(label(m, k));
                  }
                else
                  candidate.minor.push_back(c);
              }
          if (candidate.major.size() >= 2)
            return candidate;
        }

      // Less than a factor 2 wide: a linear 1, 2 or 5 x 10^k step with 2 to 6 ticks.
      Axis axis;
      axis.lo       = std::pow(10., scale.lo);
      axis.hi       = std::pow(10., scale.hi);
      double decade = std::pow(10., std::floor(std::log10((axis.hi - axis.lo) / 10.)));
      const double factors[3] = {1., 2., 5.};
      for (unsigned int k = 0;; ++k)
        {
          axis.step = factors[k % 3] * decade;
          axis.first =
            std::max(1LL, static_cast<long long>(std::ceil(axis.lo / axis.step - 1e-9)));
          axis.last = static_cast<long long>(std::floor(axis.hi / axis.step + 1e-9));
          if (axis.last - axis.first + 1 <= 6)
            break;
          if (k % 3 == 2)
            decade *= 10.;
        }
      if (axis.last < axis.first) // cannot happen for a range wider than round-off
        axis.last = axis.first;
      for (long long i = axis.first; i <= axis.last; ++i)
        scale.major.push_back(std::log10(static_cast<double>(i) * axis.step));
      scale.labels = tick_labels(axis);
      return scale;
    }

    // Whether the grid lines, minor ones included, are at least 3 px apart on an axis
    // `pixels` long.
    bool
    minor_grid_fits(const Scale &scale, const int pixels)
    {
      std::vector<double> lines = scale.major;
      lines.insert(lines.end(), scale.minor.begin(), scale.minor.end());
      std::sort(lines.begin(), lines.end());
      const double per_unit = std::abs(pixels) / (scale.hi - scale.lo);
      for (std::size_t i = 1; i < lines.size(); ++i)
        if ((lines[i] - lines[i - 1]) * per_unit < 3.)
          return false;
      return true;
    }

    // Pixel of an axis coordinate on an axis running from pixel p0 (at lo) to p1 (at hi).
    int
    to_pixel(const double value, const Scale &scale, const int p0, const int p1)
    {
      const double p = p0 + (value - scale.lo) / (scale.hi - scale.lo) * (p1 - p0);
      return static_cast<int>(std::lround(std::clamp(p, -1e6, 1e6)));
    }

    void
    draw_panel(Image &image, const PlotPanel &panel, const int top, const int height)
    {
      // Points drawn: finite, and positive on a log axis. Their axis coordinates.
      const auto drawn = [&panel](const double x, const double y) {
        return std::isfinite(x) && std::isfinite(y) && (!panel.log_x || x > 0.) &&
               (!panel.log_y || y > 0.);
      };
      const auto x_coordinate = [&panel](const double x) {
        return panel.log_x ? std::log10(x) : x;
      };
      const auto y_coordinate = [&panel](const double y) {
        return panel.log_y ? std::log10(y) : y;
      };

      // Data ranges.
      double x_min = HUGE_VAL, x_max = -HUGE_VAL, y_min = HUGE_VAL, y_max = -HUGE_VAL;
      for (const PlotSeries &s : panel.series)
        {
          if (s.x.size() != s.y.size())
            throw std::invalid_argument("write_line_plot: series '" + s.label +
                                        "' has x and y of different lengths");
          for (std::size_t i = 0; i < s.x.size(); ++i)
            if (drawn(s.x[i], s.y[i]))
              {
                x_min = std::min(x_min, x_coordinate(s.x[i]));
                x_max = std::max(x_max, x_coordinate(s.x[i]));
                y_min = std::min(y_min, y_coordinate(s.y[i]));
                y_max = std::max(y_max, y_coordinate(s.y[i]));
              }
        }
      const Scale x_axis =
        panel.log_x ? make_log_scale(x_min, x_max) : make_linear_scale(x_min, x_max);
      const Scale y_axis =
        panel.log_y ? make_log_scale(y_min, y_max) : make_linear_scale(y_min, y_max);
      const std::vector<std::string> &x_labels = x_axis.labels;
      const std::vector<std::string> &y_labels = y_axis.labels;

      // Layout: title row on top, tick labels and x label below, tick labels and the
      // vertical y label on the left.
      constexpr int tick          = 5;
      int           y_label_width = 0;
      for (const std::string &label : y_labels)
        y_label_width = std::max(y_label_width, text_width(label));
      const int box_left =
        6 + (panel.y_label.empty() ? 0 : glyph_rows + 6) + y_label_width + 4 + tick;
      const int box_right =
        image.width - 1 - std::max(12, text_width(x_labels.back()) / 2 + 4);
      const int box_top    = top + 22;
      const int box_bottom = top + height - 1 - (tick + 4 + glyph_rows + 4) -
                             (panel.x_label.empty() ? 0 : glyph_rows + 6);
      if (box_right - box_left < 40 || box_bottom - box_top < 40)
        throw std::invalid_argument(
          "write_line_plot: plot size too small for its labels");
      const auto px = [&](const double x) {
        return to_pixel(x, x_axis, box_left, box_right);
      };
      const auto py = [&](const double y) {
        return to_pixel(y, y_axis, box_bottom, box_top);
      };

      // Grid (minor lines first, if not too dense), then data clipped to the inside of
      // the box, then the box itself.
      if (minor_grid_fits(x_axis, box_right - box_left))
        for (const double c : x_axis.minor)
          image.fill(px(c), box_top, px(c), box_bottom, minor_grey);
      if (minor_grid_fits(y_axis, box_bottom - box_top))
        for (const double c : y_axis.minor)
          image.fill(box_left, py(c), box_right, py(c), minor_grey);
      for (const double c : x_axis.major)
        image.fill(px(c), box_top, px(c), box_bottom, grid_grey);
      for (const double c : y_axis.major)
        image.fill(box_left, py(c), box_right, py(c), grid_grey);
      image.clip(box_left + 1, box_top + 1, box_right - 1, box_bottom - 1);
      for (const PlotSeries &s : panel.series)
        {
          int  dash = 0, x_prev = 0, y_prev = 0;
          bool connected = false;
          for (std::size_t i = 0; i < s.x.size(); ++i)
            {
              if (!drawn(s.x[i], s.y[i]))
                {
                  connected = false;
                  continue;
                }
              const int x = px(x_coordinate(s.x[i])), y = py(y_coordinate(s.y[i]));
              if (s.line && connected)
                draw_line(
                  image, x_prev, y_prev, x, y, s.color, s.dashed ? &dash : nullptr);
              else if (!s.markers)
                dot(image, x, y, s.color); // visible even if isolated
              x_prev    = x;
              y_prev    = y;
              connected = true;
            }
          if (s.markers) // on top of the series' own line
            for (std::size_t i = 0; i < s.x.size(); ++i)
              if (drawn(s.x[i], s.y[i]))
                marker(image,
                       px(x_coordinate(s.x[i])),
                       py(y_coordinate(s.y[i])),
                       s.color);
        }
      image.reset_clip();
      image.fill(box_left, box_top, box_right, box_top, black);
      image.fill(box_left, box_bottom, box_right, box_bottom, black);
      image.fill(box_left, box_top, box_left, box_bottom, black);
      image.fill(box_right, box_top, box_right, box_bottom, black);

      // Ticks and their labels.
      for (std::size_t i = 0; i < x_axis.major.size(); ++i)
        {
          const int          x     = px(x_axis.major[i]);
          const std::string &label = x_labels[i];
          image.fill(x, box_bottom + 1, x, box_bottom + tick, black);
          draw_text(
            image, label, x - text_width(label) / 2, box_bottom + tick + 4, black);
        }
      for (std::size_t i = 0; i < y_axis.major.size(); ++i)
        {
          const int          y     = py(y_axis.major[i]);
          const std::string &label = y_labels[i];
          image.fill(box_left - tick, y, box_left - 1, y, black);
          draw_text(image, label, box_left - tick - 4 - text_width(label), y - 3, black);
        }

      // Legend in the top-right corner of the box: per series a short line (if drawn as
      // a line), a marker in its middle (if drawn with markers) and the label.
      int n_entries = 0, legend_text_width = 0;
      for (const PlotSeries &s : panel.series)
        if (!s.label.empty())
          {
            ++n_entries;
            legend_text_width = std::max(legend_text_width, text_width(s.label));
          }
      if (n_entries > 0)
        {
          const int right = box_right - 6,
                    left  = right - (8 + 24 + 6 + legend_text_width + 8);
          const int upper = box_top + 6, lower = upper + 6 + 12 * n_entries;
          image.fill(left, upper, right, lower, white);
          image.fill(left, upper, right, upper, black);
          image.fill(left, lower, right, lower, black);
          image.fill(left, upper, left, lower, black);
          image.fill(right, upper, right, lower, black);
          int row = 0;
          for (const PlotSeries &s : panel.series)
            if (!s.label.empty())
              {
                const int y    = upper + 9 + 12 * row++;
                int       dash = 0;
                if (s.line)
                  draw_line(image,
                            left + 8,
                            y - 1,
                            left + 8 + 24,
                            y - 1,
                            s.color,
                            s.dashed ? &dash : nullptr);
                if (s.markers)
                  marker(image, left + 8 + 12, y - 1, s.color);
                else if (!s.line)
                  dot(image, left + 8 + 12, y - 1, s.color);
                draw_text(image, s.label, left + 8 + 24 + 6, y - 3, black);
              }
        }

      // Title (bold) and axis labels, centred on the box and cut to its size.
      const int         middle  = (box_left + box_right) / 2;
      const std::string title   = fit_text(panel.title, box_right - box_left - 1);
      const std::string x_label = fit_text(panel.x_label, box_right - box_left);
      const std::string y_label = fit_text(panel.y_label, box_bottom - box_top);
      draw_text(image, title, middle - (text_width(title) + 1) / 2, top + 8, black, true);
      draw_text(image,
                x_label,
                middle - text_width(x_label) / 2,
                box_bottom + tick + 4 + glyph_rows + 6,
                black);
      draw_text(image,
                y_label,
                6,
                (box_top + box_bottom) / 2 + text_width(y_label) / 2,
                black,
                false,
                true);
    }


    void
    append_u32(std::string &out, const std::uint32_t value)
    {
      for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<char>((value >> shift) & 0xFF));
    }

    // Chunk: length, type, data, CRC-32 of type and data.
    void
    append_chunk(std::string &png, const char *type, const std::string &data)
    {
      append_u32(png, static_cast<std::uint32_t>(data.size()));
      const std::size_t start = png.size();
      png.append(type, 4);
      png += data;
      append_u32(png,
                 crc32(0,
                       reinterpret_cast<const Bytef *>(png.data() + start),
                       static_cast<uInt>(png.size() - start)));
    }

    std::string
    encode_png(const Image &image)
    {
      // Every row: filter type 0 (none), then RGB bytes.
      const std::size_t          row_bytes = 3 * static_cast<std::size_t>(image.width);
      std::vector<unsigned char> raw;
      raw.reserve((row_bytes + 1) * image.height);
      for (int y = 0; y < image.height; ++y)
        {
          raw.push_back(0);
          raw.insert(raw.end(),
                     image.pixels.begin() + y * row_bytes,
                     image.pixels.begin() + (y + 1) * row_bytes);
        }
      uLongf                     compressed_size = compressBound(raw.size());
      std::vector<unsigned char> compressed(compressed_size);
      if (compress2(compressed.data(), &compressed_size, raw.data(), raw.size(), 6) !=
          Z_OK)
        throw std::runtime_error("write_line_plot: zlib compression failed");

      std::string header;
      append_u32(header, image.width);
      append_u32(header, image.height);
      header += std::string("\x08\x02\x00\x00\x00", 5); // 8 bit RGB, no interlace
      std::string png("\x89PNG\r\n\x1a\n", 8);
      append_chunk(png, "IHDR", header);
      append_chunk(png,
                   "IDAT",
                   std::string(reinterpret_cast<const char *>(compressed.data()),
                               compressed_size));
      append_chunk(png, "IEND", "");
      return png;
    }
  } // namespace


  void
  write_line_plot(const std::string            &file,
                  const std::vector<PlotPanel> &panels,
                  const unsigned int            width,
                  const unsigned int            panel_height)
  {
    if (panels.empty())
      throw std::invalid_argument("write_line_plot: no panels for " + file);
    if (width < 200 || panel_height < 120 || width > 20000 ||
        panel_height * panels.size() > 100000)
      throw std::invalid_argument("write_line_plot: image size out of range for " + file);
    Image image(width, panel_height * panels.size());
    for (std::size_t i = 0; i < panels.size(); ++i)
      draw_panel(image, panels[i], i * panel_height, panel_height);
    const std::string png = encode_png(image);

    std::ofstream out(file, std::ios::binary);
    out.write(png.data(), png.size());
    out.close();
    if (!out)
      throw std::runtime_error("cannot write line plot " + file);
  }
} // namespace clothsim::io
