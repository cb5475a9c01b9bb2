#include "io/parameter_errors.h"

#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include "io/input_error.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>

namespace clothsim::io
{
  namespace Utilities = dealii::Utilities;

  namespace
  {
    using boost::property_tree::ptree;

    std::string
    joined(const std::string &section, const std::string &name)
    {
      return section.empty() ? name : section + "/" + name;
    }

    // Levenshtein distance, case ignored.
    unsigned int
    edit_distance(const std::string &a, const std::string &b)
    {
      std::vector<unsigned int> row(b.size() + 1);
      for (unsigned int j = 0; j <= b.size(); ++j)
        row[j] = j;
      for (unsigned int i = 1; i <= a.size(); ++i)
        {
          unsigned int diagonal = row[0];
          row[0]                = i;
          for (unsigned int j = 1; j <= b.size(); ++j)
            {
              const unsigned int above = row[j];
              const bool         same  = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
              row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
              diagonal = above;
            }
        }
      return row[b.size()];
    }

    // The candidate nearest to `name` if near enough to be a misspelling of it: at most
    // a third of its letters (at least 2) differ.
    std::string
    nearest(const std::string &name, const std::vector<std::string> &candidates)
    {
      const unsigned int limit = std::max<unsigned int>(2, name.size() / 3);
      std::string        best;
      unsigned int       best_distance = limit + 1;
      for (const std::string &candidate : candidates)
        {
          const unsigned int distance = edit_distance(name, candidate);
          if (distance < best_distance)
            {
              best          = candidate;
              best_distance = distance;
            }
        }
      return best;
    }

    // Collects the declarations from ParameterHandler's JSON tree: an entry is an object
    // with a "value"; any other object is a subsection.
    void
    collect(const ptree                                     &tree,
            const std::string                               &section,
            std::set<std::string>                           &sections,
            std::map<std::string, std::vector<std::string>> &entries)
    {
      sections.insert(section);
      for (const auto &[mangled, child] : tree)
        {
          const std::string name = demangle(mangled);
          if (child.get_child_optional("value"))
            entries[section].push_back(name);
          else
            collect(child, joined(section, name), sections, entries);
        }
    }

    // The first line of `file` that holds `text` (1-based; 0 if none).
    unsigned int
    line_of(const std::string &file, const std::string &text)
    {
      std::ifstream in(file);
      std::string   line;
      for (unsigned int n = 1; std::getline(in, line); ++n)
        if (line.find(text) != std::string::npos)
          return n;
      return 0;
    }

    // The subsection path (a/b) enclosing line `line_number` of a .prm file.
    std::string
    section_at(const std::string &file, const unsigned int line_number)
    {
      std::ifstream            in(file);
      std::vector<std::string> open;
      std::string              line;
      for (unsigned int n = 1; n < line_number && std::getline(in, line); ++n)
        {
          std::smatch words;
          if (std::regex_search(line,
                                words,
                                std::regex("^\\s*subsection\\s+(.*?)\\s*(#.*)?$")))
            open.push_back(words[1]);
          else if (std::regex_search(line, std::regex("^\\s*end\\s*(#.*)?$")) &&
                   !open.empty())
            open.pop_back();
        }
      std::string path;
      for (const std::string &section : open)
        path = joined(path, section);
      return path;
    }

    // The entry (for `section`) and text of deal.II's "does not match" and "no entry"
    // messages; {"", message} for any other.
    std::pair<std::string, std::string>
    describe(const std::string        &message,
             const std::string        &section,
             const DeclaredParameters *declared)
    {
      std::smatch match;
      if (std::regex_search(message,
                            match,
                            std::regex("The entry value (.*) for the entry named (.*) "
                                       "does not match the given pattern:? (.*)$")))
        return {joined(section, match[2]),
                "value " + std::string(match[1]) + " does not match " +
                  std::string(match[3])};
      if (std::regex_search(message,
                            match,
                            std::regex("No entry with name <([^>]*)> was declared")))
        return {joined(section, match[1]),
                "no such entry" +
                  (declared ? declared->entry_suggestion(section, match[1]) : "") +
                  " (clothsim --print-parameters lists them all)"};
      return {"", message};
    }
  } // namespace


  std::string
  demangle(const std::string &name)
  {
    std::string plain;
    for (unsigned int i = 0; i < name.size(); ++i)
      if (name[i] == '_' && i + 2 < name.size() &&
          std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
          std::isxdigit(static_cast<unsigned char>(name[i + 2])))
        {
          plain += static_cast<char>(std::stoi(name.substr(i + 1, 2), nullptr, 16));
          i += 2;
        }
      else
        plain += name[i];
    return plain;
  }


  DeclaredParameters::DeclaredParameters(const ParameterHandler &prm)
  {
    std::stringstream json;
    prm.print_parameters(json, ParameterHandler::JSON);
    ptree tree;
    boost::property_tree::read_json(json, tree);
    collect(tree, "", sections, entries);
  }


  bool
  DeclaredParameters::has_section(const std::string &path) const
  {
    return sections.count(path) > 0;
  }


  bool
  DeclaredParameters::has_entry(const std::string &path) const
  {
    const auto        slash   = path.rfind('/');
    const std::string section = slash == std::string::npos ? "" : path.substr(0, slash);
    const auto        found   = entries.find(section);
    return found != entries.end() &&
           std::count(found->second.begin(),
                      found->second.end(),
                      path.substr(slash == std::string::npos ? 0 : slash + 1)) > 0;
  }


  std::string
  DeclaredParameters::entry_suggestion(const std::string &section,
                                       const std::string &name) const
  {
    const auto  found = entries.find(section);
    std::string best =
      found == entries.end() ? std::string() : nearest(name, found->second);
    if (!best.empty())
      return "; did you mean '" + best + "'?";
    // The entry, or one spelt nearly like it, declared in another section.
    std::vector<std::string> elsewhere;
    for (const auto &[other, names] : entries)
      for (const std::string &candidate : names)
        elsewhere.push_back(joined(other, candidate));
    std::vector<std::string> names_only;
    for (const std::string &path : elsewhere)
      names_only.push_back(path.substr(path.rfind('/') + 1));
    best = nearest(name, names_only);
    if (best.empty())
      return "";
    for (const std::string &path : elsewhere)
      if (path.substr(path.rfind('/') + 1) == best)
        return "; did you mean '" + path + "', in another section?";
    return "";
  }


  std::string
  DeclaredParameters::section_suggestion(const std::string &parent,
                                         const std::string &name) const
  {
    std::vector<std::string> children;
    const std::string        prefix = parent.empty() ? "" : parent + "/";
    for (const std::string &section : sections)
      if (!section.empty() && section.rfind(prefix, 0) == 0 &&
          section.find('/', prefix.size()) == std::string::npos)
        children.push_back(section.substr(prefix.size()));
    const std::string best = nearest(name, children);
    return best.empty() ? "" : "; did you mean '" + joined(parent, best) + "'?";
  }


  void
  DeclaredParameters::check_entry_path(const std::vector<std::string> &path,
                                       const std::string              &source,
                                       const unsigned int              line) const
  {
    std::string section;
    for (unsigned int i = 0; i + 1 < path.size(); ++i)
      {
        const std::string inner = joined(section, path[i]);
        if (!has_section(inner))
          throw InputError(source,
                           inner,
                           "no such section" + section_suggestion(section, path[i]) +
                             " (clothsim --print-parameters lists them all)",
                           line);
        section = inner;
      }
    if (path.empty() || !has_entry(joined(section, path.back())))
      throw InputError(source,
                       joined(section, path.empty() ? "" : path.back()),
                       "no such entry" +
                         entry_suggestion(section, path.empty() ? "" : path.back()) +
                         " (clothsim --print-parameters lists them all)",
                       line);
  }


  std::string
  one_line(const std::exception &exception)
  {
    std::string       text   = exception.what();
    const std::string marker = "Additional information:";
    const auto        pos    = text.find(marker);
    if (pos != std::string::npos)
      text = text.substr(pos + marker.size());
    const auto stacktrace = text.find("Stacktrace:");
    if (stacktrace != std::string::npos)
      text = text.substr(0, stacktrace);
    // Drop deal.II's separator lines of dashes only: a value's own minus sign stays.
    text =
      std::regex_replace(text, std::regex("(^|\\n)[ \\t]*-{3,}[ \\t]*(?=\\n|$)"), "\n");
    text = std::regex_replace(text, std::regex("\\s+"), " ");
    text = std::regex_replace(text, std::regex("^ | $"), "");
    return text;
  }


  void
  throw_prm_error(const std::string        &file,
                  const std::string        &message,
                  const DeclaredParameters &declared)
  {
    std::smatch match;
    if (!std::regex_search(message, match, std::regex("Line <([0-9]+)> of file <")))
      throw InputError(file, "", message);
    const unsigned int line    = std::stoi(match[1]);
    const std::string  section = section_at(file, line);
    // A subsection that is not declared ("subsection Matrial"); deal.II's message names
    // the line only at its start, and leaves the file's bracket open.
    std::smatch subsection;
    if (std::regex_search(message,
                          subsection,
                          std::regex("no such subsection to be entered: (.*)$")))
      {
        const std::string name = Utilities::trim(subsection[1]);
        throw InputError(file,
                         joined(section, name),
                         "no such section" + declared.section_suggestion(section, name) +
                           " (clothsim --print-parameters lists them all)",
                         line);
      }
    const std::string text =
      std::regex_search(message,
                        match,
                        std::regex("Line <[0-9]+> of file <[^>]*>: (.*)$"))
        ? std::string(match[1])
        : message;
    const auto [entry, what] = describe(text, section, &declared);
    throw InputError(file, entry, what, line);
  }


  namespace
  {
    // Walks a JSON object against the declarations: a key whose value is an object
    // without "value" is a subsection, anything else an entry.
    void
    check_json_tree(const ptree              &tree,
                    const std::string        &section,
                    const std::string        &file,
                    const DeclaredParameters &declared)
    {
      for (const auto &[key, child] : tree)
        {
          const std::string name     = demangle(key);
          const bool        is_entry = child.empty() || child.get_child_optional("value");
          const std::string path     = joined(section, name);
          const unsigned int line    = line_of(file, "\"" + key + "\"");
          if (!is_entry)
            {
              if (!declared.has_section(path))
                throw InputError(file,
                                 path,
                                 "no such section" +
                                   declared.section_suggestion(section, name) +
                                   " (clothsim --print-parameters lists them all)",
                                 line);
              check_json_tree(child, path, file, declared);
            }
          else if (!declared.has_entry(path))
            throw InputError(file,
                             path,
                             "no such entry" + declared.entry_suggestion(section, name) +
                               " (clothsim --print-parameters lists them all)",
                             line);
        }
    }
  } // namespace


  void
  check_json_names(const std::string &file, const DeclaredParameters &declared)
  {
    ptree tree;
    try
      {
        boost::property_tree::read_json(file, tree);
      }
    catch (const boost::property_tree::json_parser_error &error)
      {
        throw InputError(file, "", "not valid JSON: " + error.message(), error.line());
      }
    check_json_tree(tree, "", file, declared);
  }


  namespace
  {
    // The path (Section/Name) of the first entry of a JSON tree whose value is `value`.
    std::string
    json_entry_with_value(const ptree       &tree,
                          const std::string &section,
                          const std::string &value)
    {
      for (const auto &[key, child] : tree)
        {
          const std::string path = joined(section, demangle(key));
          if (child.empty() || child.get_child_optional("value"))
            {
              if (Utilities::trim(child.empty()
                                    ? child.data()
                                    : child.get<std::string>("value")) == value)
                return path;
            }
          else if (const std::string found = json_entry_with_value(child, path, value);
                   !found.empty())
            return found;
        }
      return "";
    }
  } // namespace


  void
  throw_json_error(const std::string &file, const std::string &message)
  {
    // A value that does not match its pattern: deal.II names the value, not the entry;
    // the entry is the first that holds that value.
    std::smatch match;
    if (std::regex_search(message,
                          match,
                          std::regex("The string <(.*)> does not match the given pattern "
                                     "<(.*)>")))
      {
        ptree tree;
        boost::property_tree::read_json(file, tree);
        const std::string value = match[1];
        const std::string entry = json_entry_with_value(tree, "", value);
        const std::string name  = entry.substr(entry.rfind('/') + 1);
        throw InputError(file,
                         entry,
                         "value " + value + " does not match " + std::string(match[2]),
                         entry.empty() ? 0 : line_of(file, "\"" + name + "\""));
      }
    const auto [entry, what] = describe(message, "", nullptr);
    if (entry.empty())
      throw InputError(file, "", what);
    // deal.II names the entry without its section: the key's line in the file.
    const std::string name = entry.substr(entry.rfind('/') + 1);
    throw InputError(file, entry, what, line_of(file, "\"" + name + "\""));
  }


  void
  apply_assignment(ParameterHandler         &prm,
                   const std::string        &assignment,
                   const DeclaredParameters &declared)
  {
    const std::string source = "--set \"" + assignment + "\"";
    const auto        equals = assignment.find('=');
    if (equals == std::string::npos)
      throw InputError(source, "", "expected \"Section/Name=value\"");
    const auto path =
      dealii::Utilities::split_string_list(assignment.substr(0, equals), '/');
    const std::string value = dealii::Utilities::trim(assignment.substr(equals + 1));
    declared.check_entry_path(path, source, 0);
    std::string entry;
    for (const std::string &part : path)
      entry = joined(entry, part);
    try
      {
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          prm.enter_subsection(path[i]);
        prm.set(path.back(), value);
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          prm.leave_subsection();
      }
    catch (const std::exception &e)
      {
        const std::string text = one_line(e);
        std::smatch       match;
        if (std::regex_search(
              text, match, std::regex("does not match the given pattern:? <?(\\[.*\\])")))
          throw InputError(source,
                           entry,
                           "value " + value + " does not match " + std::string(match[1]));
        throw InputError(source, entry, text);
      }
  }
} // namespace clothsim::io
