#pragma once

// Fabric presets by name (Material/Preset): measured values of real fabrics, each with
// its source, in SI units. A preset supplies the defaults of the Material entries it
// names; any of them set in the parameter file or with --set overrides it.

#include <string>
#include <utility>
#include <vector>

namespace clothsim
{
  struct FabricPreset
  {
    std::string name;
    // (Material entry, value) pairs, values as a parameter file would spell them.
    std::vector<std::pair<std::string, std::string>> values;
    std::string                                      source;
  };

  // All presets, in the order the documentation lists them.
  const std::vector<FabricPreset> &
  fabric_presets();

  // The preset of that name, or null for "none" (or an unknown name).
  const FabricPreset *
  find_fabric_preset(const std::string &name);

  // "none|cotton|..." for the entry's pattern.
  std::string
  fabric_preset_names();

  // The presets with their expanded values and sources, for the entry's documentation.
  std::string
  fabric_preset_documentation();
} // namespace clothsim
