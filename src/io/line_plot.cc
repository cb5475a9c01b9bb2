// Line plots drawn into an RGB buffer panel by panel: axes box, grid, data as
// Bresenham lines, dots or disc markers, ticks, legend and labels. Scales and ticks are
// in io/line_plot_axes.cc, the bitmap font in io/line_plot_font.cc, the PNG encoder in
// io/line_plot_png.cc.

#include "io/line_plot.h"

#include "io/line_plot_detail.h"
#include "io/output_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace clothsim::io
{
  using namespace detail;


  namespace
  {
    constexpr Color black{{0, 0, 0}};
    constexpr Color white{{255, 255, 255}};
    constexpr Color grid_grey{{225, 225, 225}};
    constexpr Color minor_grey{{240, 240, 240}}; // minor grid of log axes


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

    write_file_atomically(file, [&png](std::ostream &out) {
      out.write(png.data(), png.size());
    });
  }
} // namespace clothsim::io
