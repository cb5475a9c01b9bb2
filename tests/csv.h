#pragma once

// Reading the CSV files that clothsim writes (one header line, comma-separated), for
// tests.

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace clothsim::test
{
  struct Csv
  {
    std::vector<std::string>              header;
    std::vector<std::vector<std::string>> rows;

    unsigned int
    column(const std::string &name) const
    {
      for (unsigned int c = 0; c < header.size(); ++c)
        if (header[c] == name)
          return c;
      throw std::runtime_error("no column " + name);
    }

    double
    number(const unsigned int row, const std::string &name) const
    {
      return std::stod(rows.at(row).at(column(name)));
    }
  };

  inline std::vector<std::string>
  split(const std::string &line)
  {
    std::vector<std::string> fields;
    std::stringstream        stream(line);
    std::string              field;
    while (std::getline(stream, field, ','))
      fields.push_back(field);
    return fields;
  }

  inline Csv
  read_csv(const std::string &file)
  {
    std::ifstream in(file);
    if (!in)
      throw std::runtime_error("cannot read " + file);
    Csv         csv;
    std::string line;
    std::getline(in, line);
    csv.header = split(line);
    while (std::getline(in, line))
      if (!line.empty())
        csv.rows.push_back(split(line));
    return csv;
  }
} // namespace clothsim::test
