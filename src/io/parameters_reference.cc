// clothsim --print-parameters: every declared entry with its default, pattern and
// documentation, read back from ParameterHandler's JSON output.

#include "io/parameters.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <sstream>

namespace clothsim
{
  namespace
  {
    // ParameterHandler stores names with every character outside [A-Za-z0-9] as "_" and
    // two hex digits.
    std::string
    demangle(const std::string &name)
    {
      std::string plain;
      for (unsigned int i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size())
          {
            plain += static_cast<char>(std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
          }
        else
          plain += name[i];
      return plain;
    }

    // Walks ParameterHandler's JSON tree: entries carry "default_value",
    // "pattern_description" and "documentation"; anything else is a subsection.
    void
    print_entries(std::ostream                      &out,
                  const boost::property_tree::ptree &tree,
                  const std::string                 &path)
    {
      for (const auto &[name, child] : tree)
        {
          const std::string demangled = demangle(name);
          if (child.get_optional<std::string>("default_value"))
            out << path << demangled << " = " << child.get<std::string>("default_value")
                << "\n    allowed: " << child.get<std::string>("pattern_description")
                << "\n    " << child.get<std::string>("documentation") << "\n\n";
          else
            print_entries(out, child, path + demangled + "/");
        }
    }
  } // namespace


  void
  print_parameter_reference(std::ostream &out)
  {
    ParameterHandler prm;
    Parameters::declare_parameters(prm);
    std::stringstream json;
    prm.print_parameters(json, ParameterHandler::JSON);
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    out << "clothsim parameters: Section/Name = default, allowed values, meaning and "
           "unit.\n"
           "Set them in a .prm file ('subsection Section', 'set Name = value', 'end') or "
           "with\n"
           "--set \"Section/Name=value\".\n\n";
    print_entries(out, tree, "");
  }
} // namespace clothsim
