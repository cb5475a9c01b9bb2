// Reading STL (ASCII and binary) and OBJ files into triangle soups: the lines, their
// tokens and numbers, and the checks that can name a line.

#include "io/input_error.h"
#include "mesh/surface_mesh_detail.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>

namespace clothsim::mesh::detail
{
  namespace
  {
    // Binary STL: an 80-byte header, the number of facets (uint32), then per facet
    // 50 bytes: normal and three corners (12 float32, little-endian), 2 attribute bytes.
    constexpr std::size_t stl_header_bytes = 84;
    constexpr std::size_t stl_facet_bytes  = 50;


    std::string
    line_entry(const std::size_t line)
    {
      return "line " + std::to_string(line);
    }

    // A token quoted for an error message (cut after 40 characters).
    std::string
    quoted(const std::string_view token)
    {
      return "'" +
             (token.size() <= 40 ? std::string(token)
                                 : std::string(token.substr(0, 40)) + "...") +
             "'";
    }

    std::string
    lower_case(std::string_view text)
    {
      std::string lower(text);
      for (char &c : lower)
        c = std::tolower(static_cast<unsigned char>(c));
      return lower;
    }

    // The whitespace-separated tokens of `line`.
    std::vector<std::string_view>
    split(const std::string_view line)
    {
      std::vector<std::string_view> tokens;
      const char                   *space = " \t\r\v\f";
      std::size_t                   start = line.find_first_not_of(space);
      while (start != std::string_view::npos)
        {
          const std::size_t end = line.find_first_of(space, start);
          tokens.push_back(line.substr(start, end - start));
          start =
            end == std::string_view::npos ? end : line.find_first_not_of(space, end);
        }
      return tokens;
    }

    // Calls f(number, line) for each line of `text` (numbered from 1).
    template <typename Function>
    void
    for_each_line(const std::string &text, Function &&f)
    {
      std::size_t start = 0, number = 1;
      while (start < text.size())
        {
          std::size_t end = text.find('\n', start);
          if (end == std::string::npos)
            end = text.size();
          f(number, std::string_view(text).substr(start, end - start));
          start = end + 1;
          ++number;
        }
    }

    // The whole token as a number (C locale; a leading '+' allowed). Values beyond the
    // range of double become +-inf or 0, as strtod gives them.
    bool
    parse_number(std::string_view token, double &value)
    {
      if (token.size() > 1 && token[0] == '+' && token[1] != '-')
        token.remove_prefix(1);
      const char *const end    = token.data() + token.size();
      const auto        result = std::from_chars(token.data(), end, value);
      if (result.ptr != end)
        return false;
      if (result.ec == std::errc::result_out_of_range)
        value = std::strtod(std::string(token).c_str(), nullptr);
      return result.ec == std::errc() || result.ec == std::errc::result_out_of_range;
    }

    bool
    parse_integer(const std::string_view token, long long &value)
    {
      const char *const end    = token.data() + token.size();
      const auto        result = std::from_chars(token.data(), end, value);
      return !token.empty() && result.ec == std::errc() && result.ptr == end;
    }

    // Three finite coordinates from tokens[1..3], or an InputError on `line`.
    Point<3>
    parse_point(const std::string                   &file,
                const std::size_t                    line,
                const std::vector<std::string_view> &tokens)
    {
      Point<3> point;
      for (unsigned int d = 0; d < 3; ++d)
        {
          if (!parse_number(tokens[d + 1], point[d]))
            throw InputError(file,
                             line_entry(line),
                             quoted(tokens[d + 1]) + " is not a number");
          if (!std::isfinite(point[d]))
            throw InputError(file,
                             line_entry(line),
                             "non-finite coordinate " + quoted(tokens[d + 1]));
        }
      return point;
    }


    // STL files

    Soup
    read_ascii_stl(const std::string &file, const std::string &text)
    {
      // Where we are: each keyword is allowed in one state and leads to the next.
      enum class State
      {
        outside,
        solid,
        facet,
        loop,
        end_of_loop
      };
      const char *expected[] = {"'solid'",
                                "'facet' or 'endsolid'",
                                "'outer loop'",
                                "'vertex' or 'endloop'",
                                "'endfacet'"};

      Soup soup;
      soup.kind              = "facet";
      State       state      = State::outside;
      std::size_t n_corners  = 0;
      std::size_t last_line  = 0;
      std::size_t solid_line = 0;
      const auto  unexpected = [&](const std::size_t line, const std::string_view found) {
        return InputError(file,
                          line_entry(line),
                          "expected " + std::string(expected[int(state)]) + ", found " +
                            quoted(found));
      };

      for_each_line(text, [&](const std::size_t line, const std::string_view content) {
        last_line                                  = line;
        const std::vector<std::string_view> tokens = split(content);
        if (tokens.empty())
          return;
        const std::string keyword = lower_case(tokens[0]);
        if (state == State::outside && keyword == "solid")
          {
            state      = State::solid;
            solid_line = line;
          }
        else if (state == State::solid && keyword == "endsolid")
          state = State::outside;
        else if (state == State::solid && keyword == "facet")
          {
            // The normal is not used (the corners' order gives the orientation).
            state = State::facet;
            soup.triangles.emplace_back();
            soup.numbers.push_back(soup.triangles.size());
            soup.lines.push_back(line);
          }
        else if (state == State::facet && keyword == "outer" && tokens.size() == 2 &&
                 lower_case(tokens[1]) == "loop")
          {
            state     = State::loop;
            n_corners = 0;
          }
        else if (state == State::loop && keyword == "vertex")
          {
            if (tokens.size() != 4)
              throw InputError(file,
                               line_entry(line),
                               "'vertex' needs 3 coordinates, found " +
                                 std::to_string(tokens.size() - 1));
            if (n_corners == 3)
              throw InputError(file,
                               line_entry(line),
                               "a facet with more than 3 vertices; only triangles");
            soup.triangles.back()[n_corners++] = soup.points.size();
            soup.points.push_back(parse_point(file, line, tokens));
          }
        else if (state == State::loop && keyword == "endloop")
          {
            if (n_corners != 3)
              throw InputError(file,
                               line_entry(line),
                               "a facet with " + std::to_string(n_corners) +
                                 " vertices; 3 expected");
            state = State::end_of_loop;
          }
        else if (state == State::end_of_loop && keyword == "endfacet")
          state = State::solid;
        else
          throw unexpected(line, tokens[0]);
      });

      if (state != State::outside)
        throw InputError(file,
                         line_entry(last_line),
                         "the file ends inside the solid begun on line " +
                           std::to_string(solid_line) + " (expected " +
                           expected[int(state)] + ")");
      return soup;
    }


    // A little-endian float32 from 4 bytes.
    float
    read_float(const char *bytes)
    {
      std::uint32_t bits = 0;
      for (unsigned int i = 0; i < 4; ++i)
        bits |= std::uint32_t(static_cast<unsigned char>(bytes[i])) << (8 * i);
      float value;
      std::memcpy(&value, &bits, sizeof(value));
      return value;
    }

    Soup
    read_binary_stl(const std::string &content)
    {
      const std::size_t n_facets = (content.size() - stl_header_bytes) / stl_facet_bytes;
      Soup              soup;
      soup.kind = "facet";
      soup.points.reserve(3 * n_facets);
      for (std::size_t f = 0; f < n_facets; ++f)
        {
          // Skip the normal: the corners' order gives the orientation.
          const char *corners =
            content.data() + stl_header_bytes + f * stl_facet_bytes + 12;
          for (unsigned int c = 0; c < 3; ++c)
            soup.points.emplace_back(read_float(corners + 12 * c),
                                     read_float(corners + 12 * c + 4),
                                     read_float(corners + 12 * c + 8));
          soup.triangles.push_back({{3 * f, 3 * f + 1, 3 * f + 2}});
          soup.numbers.push_back(f + 1);
        }
      return soup;
    }

    // No control characters other than white space.
    bool
    is_text(const std::string &content)
    {
      return std::none_of(content.begin(), content.end(), [](const char c) {
        const unsigned char byte = c;
        return byte < 32 && !std::isspace(byte);
      });
    }

  } // namespace


  // Binary if the size is 84 + 50 n for the n of the header (an ASCII file cannot
  // match: its bytes 80-83 would announce at least 0x09090909 facets); else ASCII if
  // it is text; else a binary file of the wrong size.
  Soup
  read_stl(const std::string &file, const std::string &content)
  {
    std::uint64_t n_facets = 0;
    if (content.size() >= stl_header_bytes)
      for (unsigned int i = 0; i < 4; ++i)
        n_facets |= std::uint64_t(static_cast<unsigned char>(content[80 + i])) << (8 * i);
    const std::uint64_t size = stl_header_bytes + stl_facet_bytes * n_facets;
    if (content.size() >= stl_header_bytes && content.size() == size)
      return read_binary_stl(content);
    if (is_text(content))
      return read_ascii_stl(file, content);

    std::ostringstream message;
    if (content.size() < stl_header_bytes)
      message << "truncated binary STL: " << content.size()
              << " bytes, shorter than its 84-byte header";
    else
      message << (content.size() < size ? "truncated binary STL"
                                        : "binary STL longer than its header says")
              << ": the header announces " << n_facets << " facets (84 + 50 * "
              << n_facets << " = " << size << " bytes), the file has " << content.size()
              << " bytes";
    throw InputError(file, "", message.str());
  }


  // ---------------------------------------------------------------------------------
  // OBJ files

  namespace
  {
    // The vertex index of a face entry "i", "i/t", "i//n" or "i/t/n".
    long long
    parse_face_entry(const std::string     &file,
                     const std::size_t      line,
                     const std::string_view entry)
    {
      long long                     index = 0, other = 0;
      std::vector<std::string_view> fields;
      for (std::size_t start = 0;;)
        {
          const std::size_t slash = entry.find('/', start);
          fields.push_back(entry.substr(start, slash - start));
          if (slash == std::string_view::npos)
            break;
          start = slash + 1;
        }
      bool valid = fields.size() <= 3 && parse_integer(fields[0], index) && index != 0;
      for (std::size_t i = 1; i < fields.size(); ++i)
        valid &= fields[i].empty() || parse_integer(fields[i], other);
      if (!valid)
        throw InputError(file,
                         line_entry(line),
                         quoted(entry) +
                           " is not a face entry (i, i/t, i//n or i/t/n with a vertex "
                           "index i != 0)");
      return index;
    }
  } // namespace


  Soup
  read_obj(const std::string &file, const std::string &text)
  {
    Soup soup;
    soup.kind = "line";
    for_each_line(text, [&](const std::size_t line, std::string_view content) {
      content                                    = content.substr(0, content.find('#'));
      const std::vector<std::string_view> tokens = split(content);
      if (tokens.empty())
        return;
      if (tokens[0] == "v")
        {
          // x y z, and optionally w or a colour: all numbers.
          double value;
          for (std::size_t i = 4; i < tokens.size(); ++i)
            if (!parse_number(tokens[i], value))
              throw InputError(file,
                               line_entry(line),
                               quoted(tokens[i]) + " is not a number");
          if (tokens.size() < 4)
            throw InputError(file,
                             line_entry(line),
                             "'v' needs 3 coordinates, found " +
                               std::to_string(tokens.size() - 1));
          soup.points.push_back(parse_point(file, line, tokens));
        }
      else if (tokens[0] == "f")
        {
          if (tokens.size() < 4)
            throw InputError(file,
                             line_entry(line),
                             "a face needs at least 3 vertices, found " +
                               std::to_string(tokens.size() - 1));
          std::vector<std::size_t> corners;
          for (std::size_t i = 1; i < tokens.size(); ++i)
            {
              long long index = parse_face_entry(file, line, tokens[i]);
              if (index < 0)
                {
                  // Relative: -1 is the last vertex so far.
                  if (-index > static_cast<long long>(soup.points.size()))
                    throw InputError(file,
                                     line_entry(line),
                                     "vertex index " + std::to_string(index) +
                                       " out of range: " +
                                       std::to_string(soup.points.size()) +
                                       " vertices before this line");
                  index += soup.points.size() + 1;
                }
              // Positive indices may refer to vertices further down: checked
              // at the end.
              corners.push_back(index - 1);
            }
          // A fan around the first corner.
          for (std::size_t k = 1; k + 1 < corners.size(); ++k)
            {
              soup.triangles.push_back({{corners[0], corners[k], corners[k + 1]}});
              soup.numbers.push_back(line);
            }
        }
      // Texture coordinates, normals, groups, materials, lines, ...: not needed.
    });

    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
      for (const std::size_t corner : soup.triangles[t])
        if (corner >= soup.points.size())
          throw InputError(file,
                           soup.name(t),
                           "vertex index " + std::to_string(corner + 1) +
                             " out of range: the file has " +
                             std::to_string(soup.points.size()) + " vertices");
    return soup;
  }
} // namespace clothsim::mesh::detail
