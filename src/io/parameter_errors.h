#pragma once

// Input errors in parameters, in one format for .prm files, JSON files and --set:
//   <file>:<line>: <Section/Entry>: <what was expected>
// (InputError's format; JSON lines are those of the entry's key, --set names the
// assignment instead of a file), with "did you mean ...?" for names that are not
// declared: the declared entry or subsection nearest in spelling, or the same entry in
// another section.

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace clothsim::io
{
  using dealii::ParameterHandler;

  // The names declared in a ParameterHandler: subsection paths and entries, as
  // "Section/Sub/Name".
  class DeclaredParameters
  {
  public:
    explicit DeclaredParameters(const ParameterHandler &prm);

    bool
    has_section(const std::string &path) const;
    bool
    has_entry(const std::string &path) const;

    // "; did you mean 'X'?" for an undeclared entry `name` in `section` ("" at the top),
    // or "" if nothing declared is near.
    std::string
    entry_suggestion(const std::string &section, const std::string &name) const;
    // The same for an undeclared subsection `name` of `parent`.
    std::string
    section_suggestion(const std::string &parent, const std::string &name) const;

    // Throws InputError(source, line) if `path` (Section/.../Name) names no declared
    // entry, or one of its sections is not declared.
    void
    check_entry_path(const std::vector<std::string> &path,
                     const std::string              &source,
                     const unsigned int              line) const;

  private:
    std::set<std::string>                           sections; // "" is the top level
    std::map<std::string, std::vector<std::string>> entries;  // section -> names
  };

  // A name as declared: ParameterHandler's JSON output writes every character outside
  // [A-Za-z0-9] as "_" and two hex digits.
  std::string
  demangle(const std::string &name);

  // A deal.II exception's "Additional information" as one line.
  std::string
  one_line(const std::exception &exception);

  // Throws the InputError for deal.II's error `message` from parsing the .prm `file`
  // ("Line <N> of file <F>: ...").
  [[noreturn]] void
  throw_prm_error(const std::string        &file,
                  const std::string        &message,
                  const DeclaredParameters &declared);

  // Checks a JSON parameter file's names against the declarations (InputError with the
  // key's line and a suggestion), before deal.II reads it; and turns deal.II's error
  // `message` from reading it into the same format.
  void
  check_json_names(const std::string &file, const DeclaredParameters &declared);
  [[noreturn]] void
  throw_json_error(const std::string &file, const std::string &message);

  // Sets --set's assignment "Section/Name=value" in `prm`: InputError in the common
  // format if the name is not declared or the value does not match its pattern.
  void
  apply_assignment(ParameterHandler         &prm,
                   const std::string        &assignment,
                   const DeclaredParameters &declared);
} // namespace clothsim::io
