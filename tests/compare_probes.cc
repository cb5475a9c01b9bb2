// compare_probes A.csv B.csv RELATIVE ABSOLUTE [UNTIL]
// Compares two probes.csv files row by row (same steps, times and probes; times to
// RELATIVE, since an arc-length path's load factors are computed) and their
// positions and displacements, or two reactions.csv files (same steps, times and
// groups) and their centres, forces and moments: every number after the probe or group
// column, |a - b| <= max(ABSOLUTE, RELATIVE * max(|a|, |b|)). With UNTIL (s), only the
// rows up to that time, in both files: for a motion that amplifies round-off (a fold),
// whose later rows depend on the last bits of the BLAS' kernels. Prints the worst
// deviation.

#include "csv.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

int
main(int argc, char **argv)
{
  if (argc != 5 && argc != 6)
    {
      std::cerr << "usage: compare_probes A.csv B.csv RELATIVE ABSOLUTE [UNTIL]\n";
      return 2;
    }
  using namespace clothsim::test;
  Csv          a = read_csv(argv[1]), b = read_csv(argv[2]);
  const double relative = std::stod(argv[3]), absolute = std::stod(argv[4]);
  if (argc == 6)
    {
      const double until = std::stod(argv[5]);
      for (Csv *csv : {&a, &b})
        {
          const unsigned int time = csv->column("time");
          csv->rows.erase(std::remove_if(csv->rows.begin(),
                                         csv->rows.end(),
                                         [&](const std::vector<std::string> &row) {
                                           return std::stod(row.at(time)) > until;
                                         }),
                          csv->rows.end());
        }
    }
  if (a.header != b.header || a.rows.size() != b.rows.size() || a.rows.empty())
    {
      std::cout << "FAILED: different headers or row counts (" << a.rows.size() << " vs "
                << b.rows.size() << ")\n";
      return 1;
    }
  // The row's name column: 'probe' (probes.csv) or 'group' (reactions.csv).
  const bool reactions =
    std::find(a.header.begin(), a.header.end(), "group") != a.header.end();
  const std::string  key   = reactions ? "group" : "probe";
  const unsigned int first = a.column(key) + 1;
  double             worst = 0., worst_relative = 0.;
  bool               passed = true;
  for (unsigned int r = 0; r < a.rows.size(); ++r)
    {
      if (a.rows[r][a.column(key)] != b.rows[r][b.column(key)] ||
          a.rows[r][a.column("step")] != b.rows[r][b.column("step")] ||
          std::abs(a.number(r, "time") - b.number(r, "time")) >
            std::max(1e-12, relative * std::abs(a.number(r, "time"))))
        {
          std::cout << "FAILED: row " << r + 1 << " is a different step or " << key
                    << "\n";
          return 1;
        }
      for (unsigned int c = first; c < a.header.size(); ++c)
        {
          const double x = std::stod(a.rows[r].at(c)), y = std::stod(b.rows[r].at(c));
          const double deviation = std::abs(x - y);
          const double scale     = std::max(std::abs(x), std::abs(y));
          worst                  = std::max(worst, deviation);
          if (scale > absolute)
            worst_relative = std::max(worst_relative, deviation / scale);
          if (deviation > std::max(absolute, relative * scale))
            passed = false;
        }
    }
  std::cout << a.rows.size() << " rows; largest deviation " << worst
            << ", largest relative deviation (values above " << absolute << ") "
            << worst_relative << "\n"
            << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
