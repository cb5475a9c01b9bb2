// Checks that an output directory holds only whole files, as a run must leave it however
// it ended (completed, failed, interrupted, disk full):
//  - every .csv ends with a newline and every row has as many fields as its header;
//  - solution.pvd (if any) is complete XML, and every file it lists exists and is
//    complete (a .vtu ends with </VTKFile>; a .pvtu's pieces exist and are complete);
//  - no file is left under a temporary name (*.partial);
//  - with --last-time T: the last frame in solution.pvd (if any) and the last rows of
//    probes.csv are at time T (relative 1e-5: T as a log prints it), i.e. the state
//    where the run stopped was written.
// Usage: check_outputs OUTPUT_DIR [--last-time T]
// Prints what it found; exit code 0 if all holds, 1 otherwise.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  int n_failures = 0;

  void
  fail(const std::string &message)
  {
    std::cerr << "FAIL: " << message << '\n';
    ++n_failures;
  }

  std::string
  read(const fs::path &file)
  {
    std::ifstream      in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  unsigned int
  n_fields(const std::string &line)
  {
    unsigned int n        = 1;
    bool         in_quote = false;
    for (const char c : line)
      if (c == '"')
        in_quote = !in_quote;
      else if (c == ',' && !in_quote)
        ++n;
    return n;
  }

  // Returns the time of the last row (column "time"), or NaN.
  double
  check_csv(const fs::path &file)
  {
    const std::string text = read(file);
    if (text.empty() || text.back() != '\n')
      {
        fail(file.string() + " does not end with a whole row");
        return NAN;
      }
    std::istringstream       lines(text);
    std::string              line;
    std::vector<std::string> rows;
    while (std::getline(lines, line))
      rows.push_back(line);
    const unsigned int expected = n_fields(rows.front());
    for (std::size_t r = 1; r < rows.size(); ++r)
      if (n_fields(rows[r]) != expected)
        fail(file.string() + " row " + std::to_string(r) + " has " +
             std::to_string(n_fields(rows[r])) + " fields, the header " +
             std::to_string(expected));
    std::cout << file.filename().string() << ": " << rows.size() - 1 << " rows\n";
    // The time column is the second in probes.csv and statistics.csv.
    if (rows.size() < 2 || rows.front().rfind("step,time,", 0) != 0)
      return NAN;
    std::istringstream last(rows.back());
    std::string        step, time;
    std::getline(last, step, ',');
    std::getline(last, time, ',');
    return std::stod(time);
  }

  bool
  complete_vtk(const fs::path &file)
  {
    if (!fs::exists(file))
      {
        fail(file.string() + " is listed but missing");
        return false;
      }
    const std::string text = read(file);
    const auto        end  = text.rfind("</VTKFile>");
    if (end == std::string::npos ||
        text.find_first_not_of(" \n", end + 10) != std::string::npos)
      {
        fail(file.string() + " is not complete");
        return false;
      }
    return true;
  }

  // Returns the last frame's time, or NaN if there is none.
  double
  check_pvd(const fs::path &directory)
  {
    const fs::path pvd = directory / "solution.pvd";
    if (!fs::exists(pvd))
      return NAN;
    if (!complete_vtk(pvd))
      return NAN;
    const std::string text = read(pvd);
    const std::regex  data_set("timestep=\"([^\"]*)\"[^>]*file=\"([^\"]*)\"");
    double            last = NAN;
    unsigned int      n    = 0;
    for (std::sregex_iterator match(text.begin(), text.end(), data_set), end;
         match != end;
         ++match)
      {
        ++n;
        last                 = std::stod((*match)[1]);
        const fs::path frame = directory / (*match)[2].str();
        if (!complete_vtk(frame) || frame.extension() != ".pvtu")
          continue;
        const std::string pvtu = read(frame);
        const std::regex  piece("Source=\"([^\"]*)\"");
        for (std::sregex_iterator p(pvtu.begin(), pvtu.end(), piece), stop; p != stop;
             ++p)
          complete_vtk(directory / (*p)[1].str());
      }
    std::cout << "solution.pvd: " << n << " frames, the last at t = " << last << '\n';
    return last;
  }

  bool
  same_time(const double a, const double b)
  {
    return std::abs(a - b) <= 1e-5 * std::max({1., std::abs(a), std::abs(b)});
  }
} // namespace


int
main(int argc, char **argv)
{
  if (argc != 2 && !(argc == 4 && std::string(argv[2]) == "--last-time"))
    {
      std::cerr << "usage: check_outputs OUTPUT_DIR [--last-time T]\n";
      return 2;
    }
  const fs::path directory = argv[1];
  if (!fs::is_directory(directory))
    {
      std::cerr << "FAIL: " << directory << " is not a directory\n";
      return 1;
    }
  double probes_time = NAN;
  for (const auto &entry : fs::directory_iterator(directory))
    {
      const fs::path &file = entry.path();
      if (file.extension() == ".partial")
        fail(file.string() + " is a file left under its temporary name");
      if (file.extension() == ".csv")
        {
          const double last = check_csv(file);
          if (file.filename() == "probes.csv")
            probes_time = last;
        }
    }
  const double frame_time = check_pvd(directory);
  if (argc == 4)
    {
      const double expected = std::stod(argv[3]);
      if (!same_time(probes_time, expected))
        fail("the last probes.csv rows are at t = " + std::to_string(probes_time) +
             ", expected " + argv[3]);
      if (!std::isnan(frame_time) && !same_time(frame_time, expected))
        fail("the last frame is at t = " + std::to_string(frame_time) + ", expected " +
             argv[3]);
    }
  std::cout << (n_failures == 0 ? "outputs whole\n" : "outputs damaged\n");
  return n_failures == 0 ? 0 : 1;
}
