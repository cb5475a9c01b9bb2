// Axis scales of the line plots: ranges with margins, "nice" linear ticks and their
// labels, decades and minor grid lines of log axes, mapping to pixels.

#include "io/line_plot_detail.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace clothsim::io::detail
{
  namespace
  {
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
  } // namespace


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

  int
  to_pixel(const double value, const Scale &scale, const int p0, const int p1)
  {
    const double p = p0 + (value - scale.lo) / (scale.hi - scale.lo) * (p1 - p0);
    return static_cast<int>(std::lround(std::clamp(p, -1e6, 1e6)));
  }
} // namespace clothsim::io::detail
