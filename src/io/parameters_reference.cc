// clothsim --print-parameters [text|json]: every declared entry with its default, pattern
// and documentation, read back from ParameterHandler's JSON output.

#include "io/parameter_errors.h"
#include "io/parameters.h"

#include <deal.II/base/parameter_handler.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <cstdio>
#include <sstream>

namespace clothsim
{
  namespace
  {
    using boost::property_tree::ptree;

    bool
    is_entry(const ptree &node)
    {
      return node.get_optional<std::string>("default_value").has_value();
    }

    // Walks ParameterHandler's JSON tree: entries carry "default_value",
    // "pattern_description" and "documentation"; anything else is a subsection.
    void
    print_entries(std::ostream &out, const ptree &tree, const std::string &path)
    {
      for (const auto &[name, child] : tree)
        {
          const std::string demangled = io::demangle(name);
          if (is_entry(child))
            out << path << demangled << " = " << child.get<std::string>("default_value")
                << "\n    allowed: " << child.get<std::string>("pattern_description")
                << "\n    " << child.get<std::string>("documentation") << "\n\n";
          else
            print_entries(out, child, path + demangled + "/");
        }
    }

    // A JSON string: quotes, backslashes and control characters escaped, UTF-8 kept.
    std::string
    json_string(const std::string &text)
    {
      std::string quoted = "\"";
      for (const char c : text)
        if (c == '"' || c == '\\')
          quoted += std::string("\\") + c;
        else if (c == '\n')
          quoted += "\\n";
        else if (c == '\t')
          quoted += "\\t";
        else if (static_cast<unsigned char>(c) < 0x20)
          {
            char code[8];
            std::snprintf(code, sizeof(code), "\\u%04x", c);
            quoted += code;
          }
        else
          quoted += c;
      return quoted + "\"";
    }

    // Sections as objects; each entry an object with "default", "allowed" and
    // "documentation".
    void
    print_json(std::ostream &out, const ptree &tree, const std::string &indent)
    {
      bool first = true;
      out << "{";
      for (const auto &[name, child] : tree)
        {
          out << (first ? "\n" : ",\n") << indent << "  "
              << json_string(io::demangle(name)) << ": ";
          first = false;
          if (is_entry(child))
            out << "{\"default\": "
                << json_string(child.get<std::string>("default_value"))
                << ", \"allowed\": "
                << json_string(child.get<std::string>("pattern_description"))
                << ", \"documentation\": "
                << json_string(child.get<std::string>("documentation")) << "}";
          else
            print_json(out, child, indent + "  ");
        }
      out << "\n" << indent << "}";
    }
  } // namespace


  void
  print_parameter_reference(std::ostream &out, const bool json)
  {
    ParameterHandler prm;
    Parameters::declare_parameters(prm);
    std::stringstream declarations;
    prm.print_parameters(declarations, ParameterHandler::JSON);
    ptree tree;
    boost::property_tree::read_json(declarations, tree);
    if (json)
      {
        print_json(out, tree, "");
        out << "\n";
        return;
      }
    out << "clothsim parameters: Section/Name = default, allowed values, meaning and "
           "unit.\n"
           "Set them in a .prm file ('subsection Section', 'set Name = value', 'end') or "
           "with\n"
           "--set \"Section/Name=value\"; 'clothsim --print-parameters json' gives the "
           "same as JSON.\n\n";
    print_entries(out, tree, "");
  }
} // namespace clothsim
