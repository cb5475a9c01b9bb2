// Mutations for tests/fuzz_inputs.cc: byte-level ones (bit flips, deleted, inserted and
// repeated spans, truncation, lines spliced in from any seed) and structured ones of
// parameter files (an entry's value replaced by a hostile token, a dropped 'end', a
// repeated subsection, an INCLUDE) and of gmsh meshes (a token replaced, a $Section
// marker dropped or a section repeated, another format header). Each returns the mutant
// and says what it changed, with byte and line, in `description`. Deterministic: random
// numbers come from std::mt19937's raw output only.

#pragma once

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace clothsim::fuzz
{
  // A number in [0, n) from std::mt19937's raw output: its sequence is fixed by the
  // standard, the <random> distributions' are not (libstdc++ and libc++ differ).
  inline std::size_t
  below(std::mt19937 &random, const std::size_t n)
  {
    return random() % n;
  }

  template <typename T>
  const T &
  pick(std::mt19937 &random, const std::vector<T> &items)
  {
    return items[below(random, items.size())];
  }

  // Splits `text` at `separator`.
  inline std::vector<std::string>
  split(const std::string &text, const char separator)
  {
    std::vector<std::string> items;
    std::istringstream       in(text);
    for (std::string item; std::getline(in, item, separator);)
      items.push_back(item);
    return items;
  }

  // Values that parsers get wrong: signs, limits, non-finite numbers, integer overflow,
  // separators and keywords, expressions that do not evaluate, group lists, special
  // files, long strings and paths, non-ASCII and control bytes.
  inline const std::vector<std::string> &
  hostile_tokens()
  {
    static const std::vector<std::string> tokens = [] {
      std::vector<std::string> tokens = split(
        "-1|0|-0|1|1e308|-1e308|1e309|1e-308|4.9e-324|nan|-nan|inf|-inf|0x1p1024|"
        "2147483647|2147483648|-2147483649|4294967296|18446744073709551616|1e|1.2.3|--1|"
        "| |+|-|.|,|;|:|=|#|\\|\"|'|(|)|1/0|0/0|sqrt(-1)|log(0)|exp(1000)|sin(|"
        "x*1e308*1e308|t^1e308|true|end|subsection|set|pinned: w|pinned: xyzxyz|"
        "pinned;pinned|a: 1, 2, 3; a: 1, 2, 3|: 1, 2, 3|1, 2|1; 2; 3; 4|$EndNodes|"
        "\"pinned\"|/|..|/dev/null|/dev/zero|/proc/self/status|\t|\r|\x1b[2J|%s%s%n|"
        "\xc3\xa9|\xff\xfe|\xc3",
        '|');
      std::string long_path; // longer than PATH_MAX
      for (int i = 0; i < 2100; ++i)
        long_path += "d/";
      for (const std::string &token : {std::string(400, '9'),
                                       std::string(5000, 'a'),
                                       std::string(300, 'n') + ".msh",
                                       long_path + "x.msh",
                                       std::string("a\0b", 3)})
        tokens.push_back(token);
      return tokens;
    }();
    return tokens;
  }


  // Printable excerpt of `text`: other bytes as \xNN, at most `max_length` characters.
  inline std::string
  escaped(const std::string &text, const std::size_t max_length = 60)
  {
    std::ostringstream out;
    for (const char c : text.substr(0, max_length))
      {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f && c != '\\')
          out << c;
        else if (c == '\n')
          out << "\\n";
        else
          out << "\\x" << std::hex << std::setw(2) << std::setfill('0') << int(byte)
              << std::dec;
      }
    if (text.size() > max_length)
      out << "...(" << text.size() << " bytes)";
    return out.str();
  }

  inline std::string
  trimmed(const std::string &text)
  {
    const auto begin = text.find_first_not_of(" \t");
    const auto end   = text.find_last_not_of(" \t\r");
    return begin == std::string::npos ? "" : text.substr(begin, end - begin + 1);
  }

  inline std::string
  join_lines(const std::vector<std::string> &lines)
  {
    std::string text;
    for (const std::string &line : lines)
      text += line + '\n';
    return text;
  }

  // 1-based line number of byte `position`.
  inline std::size_t
  line_of(const std::string &text, const std::size_t position)
  {
    return 1 + std::count(text.begin(), text.begin() + position, '\n');
  }

  // Index of a random line that starts with `prefix` (after indentation).
  inline std::size_t
  pick_line(std::mt19937                   &random,
            const std::vector<std::string> &lines,
            const char                     *prefix)
  {
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (trimmed(lines[i]).rfind(prefix, 0) == 0)
        indices.push_back(i);
    return pick(random, indices);
  }


  // What mutations draw on: the random sequence, and all seeds (splices take lines from
  // them). At most one random draw per argument list: their order is unspecified.
  struct Context
  {
    std::mt19937             random;
    std::vector<std::string> seeds;
  };

  // A mutation: the mutated text from `text`, with what it did in `description`.
  using Mutation = std::string (*)(const std::string &, Context &, std::string &);

  // `text` with the `length` bytes at `position` replaced by `insert`; that in
  // `description`.
  inline std::string
  edit(const std::string &text,
       const std::size_t  position,
       const std::size_t  length,
       const std::string &insert,
       std::string       &description)
  {
    description = "'" + escaped(text.substr(position, length)) + "' -> '" +
                  escaped(insert) + "' at byte " + std::to_string(position) + " (line " +
                  std::to_string(line_of(text, position)) + ")";
    return text.substr(0, position) + insert +
           text.substr(std::min(text.size(), position + length));
  }

  // Byte-level, by `kind`: flip a bit, delete a span, insert random bytes or a hostile
  // token, repeat a span, truncate.
  inline std::string
  mutate_bytes(const std::string &kind,
               const std::string &text,
               Context           &context,
               std::string       &description)
  {
    std::mt19937     &random   = context.random;
    const std::size_t position = below(random, text.size() + (kind[0] == 'i'));
    if (kind == "flip")
      return edit(text,
                  position,
                  1,
                  std::string(1, text[position] ^ char(1u << below(random, 8))),
                  description);
    if (kind == "delete")
      return edit(text, position, 1 + below(random, 32), "", description);
    if (kind == "repeat")
      return edit(
        text, position, 0, text.substr(position, 1 + below(random, 64)), description);
    if (kind == "truncate")
      return edit(text, position, std::string::npos, "", description);
    if (kind == "insert-token")
      return edit(text, position, 0, pick(random, hostile_tokens()), description);
    std::string bytes(1 + below(random, 8), '\0');
    for (char &byte : bytes)
      byte = char(below(random, 256));
    return edit(text, position, 0, bytes, description);
  }

  // Lines of any seed (another format, the other file kind) inserted.
  inline std::string
  splice_lines(const std::string &text, Context &context, std::string &description)
  {
    std::vector<std::string>       lines = split(text, '\n');
    const std::size_t              donor = below(context.random, context.seeds.size());
    const std::vector<std::string> from  = split(context.seeds[donor], '\n');
    const std::size_t              first = below(context.random, from.size());
    const std::size_t count = std::min(from.size() - first, 1 + below(context.random, 5));
    const std::size_t at    = below(context.random, lines.size() + 1);
    lines.insert(lines.begin() + at, from.begin() + first, from.begin() + first + count);
    description = "lines " + std::to_string(first + 1) + "-" +
                  std::to_string(first + count) + " of seed " + std::to_string(donor) +
                  " ('" + escaped(from[first], 30) + "'...) inserted before line " +
                  std::to_string(at + 1);
    return join_lines(lines);
  }

  // Parameter file: the value of a random 'set Name = value' replaced by a hostile token
  // (4 in 6), negated, or with a token appended.
  inline std::string
  replace_value(const std::string &text, Context &context, std::string &description)
  {
    std::vector<std::string> lines  = split(text, '\n');
    std::string             &line   = lines[pick_line(context.random, lines, "set ")];
    const std::size_t        equals = line.find('=');
    const std::string        old_value =
      trimmed(line.substr(equals + 1, line.find('#', equals) - equals - 1));
    const std::string &token = pick(context.random, hostile_tokens());
    const std::size_t  form  = below(context.random, 6);
    const std::string  value = form == 0   ? "-" + old_value
                               : form == 1 ? old_value + token
                                           : token;
    line                     = line.substr(0, equals + 1) + " " + value;
    description = "'" + trimmed(line.substr(0, equals)) + "' = '" + escaped(value) + "'";
    return join_lines(lines);
  }

  // Drops a line that starts with `prefix`.
  inline std::string
  drop_line(const std::string &text,
            const char        *prefix,
            Context           &context,
            std::string       &description)
  {
    std::vector<std::string> lines = split(text, '\n');
    const std::size_t        index = pick_line(context.random, lines, prefix);
    description =
      "dropped '" + lines[index] + "' (line " + std::to_string(index + 1) + ")";
    lines.erase(lines.begin() + index);
    return join_lines(lines);
  }

  // Repeats the lines from one that starts with `opens` to the next that starts with
  // `closes`.
  inline std::string
  repeat_block(const std::string &text,
               const char        *opens,
               const char        *closes,
               Context           &context,
               std::string       &description)
  {
    std::vector<std::string> lines = split(text, '\n');
    const std::size_t        first = pick_line(context.random, lines, opens);
    std::size_t              last  = std::min(first + 1, lines.size() - 1);
    while (last + 1 < lines.size() && trimmed(lines[last]).rfind(closes, 0) != 0)
      ++last;
    const std::vector<std::string> block(lines.begin() + first, lines.begin() + last + 1);
    lines.insert(lines.begin() + last + 1, block.begin(), block.end());
    description = "repeated lines " + std::to_string(first + 1) + "-" +
                  std::to_string(last + 1) + " ('" + escaped(lines[first], 30) + "')";
    return join_lines(lines);
  }

  inline std::string
  drop_end(const std::string &text, Context &context, std::string &description)
  {
    return drop_line(text, "end", context, description);
  }

  inline std::string
  repeat_subsection(const std::string &text, Context &context, std::string &description)
  {
    return repeat_block(text, "subsection ", "end", context, description);
  }

  // deal.II's 'INCLUDE file': the mutant itself (recursion) or a hostile path.
  inline std::string
  add_include(const std::string &text, Context &context, std::string &description)
  {
    std::vector<std::string>       lines = split(text, '\n');
    const std::vector<std::string> targets =
      split("mutant.prm|mutant.prm|no-such.prm|.|/dev/null|mesh.msh||" +
              std::string(5000, 'i'),
            '|');
    const std::size_t at   = below(context.random, lines.size() + 1);
    const std::string line = "INCLUDE " + pick(context.random, targets);
    lines.insert(lines.begin() + at, line);
    description = "'" + escaped(line) + "' before line " + std::to_string(at + 1);
    return join_lines(lines);
  }

  // Mesh: a whitespace-separated token (a count, tag, coordinate, name, version)
  // replaced by a hostile token.
  inline std::string
  replace_token(const std::string &text, Context &context, std::string &description)
  {
    std::vector<std::pair<std::size_t, std::size_t>> tokens; // position, length
    std::size_t begin = text.find_first_not_of(" \t\r\n");
    while (begin < text.size())
      {
        const std::size_t end =
          std::min(text.find_first_of(" \t\r\n", begin), text.size());
        if (text[begin] != '$')
          tokens.emplace_back(begin, end - begin);
        begin = text.find_first_not_of(" \t\r\n", end);
      }
    const auto [position, length] = pick(context.random, tokens);
    return edit(
      text, position, length, pick(context.random, hostile_tokens()), description);
  }

  // Mesh: a $Section marker dropped (1 in 2), or a section repeated (from its marker, or
  // from an $End marker to the next).
  inline std::string
  mutate_section(const std::string &text, Context &context, std::string &description)
  {
    if (below(context.random, 2) == 0)
      return drop_line(text, "$", context, description);
    return repeat_block(text, "$", "$End", context, description);
  }

  // Mesh: the version line after $MeshFormat replaced (versions, binary, data sizes).
  inline std::string
  replace_header(const std::string &text, Context &context, std::string &description)
  {
    std::vector<std::string>       lines   = split(text, '\n');
    const std::vector<std::string> headers = split(
      "4.1 0 8|2.2 0 8|4.1 1 8|2.2 1 8|4 0 8|3 0 8|1.0 0 8|4.1 0 4|4.1 0 0|2.2 0 -8|"
      "5.0 0 8|nan 0 8||4.1",
      '|');
    const std::size_t index = 1; // the seeds start with $MeshFormat
    lines[index]            = pick(context.random, headers);
    description = "line " + std::to_string(index + 1) + " = '" + lines[index] + "'";
    return join_lines(lines);
  }
} // namespace clothsim::fuzz
