#include "io/fabric_presets.h"

namespace clothsim
{
  namespace
  {
    // Stretch stiffness E h and Poisson ratio from the Codimensional IPC fabric presets
    // (Li, Kaufman & Jiang, ACM TOG 40(4), 2021; E, h, ν of woven fabrics from
    // tensile tests): cotton E 0.821 MPa, h 0.318 mm; wool 0.170 MPa, 0.568 mm;
    // polyester 0.478 MPa, 0.252 mm. Bending rigidity B and weight W measured on the
    // Kawabata system (KES-FB2, mean of warp and weft): Matsudaira, Masuda, Wada &
    // Yokura, J. Textile Eng. 61(6):69-73, 2015, Tables 1-2; 1 gf·cm²/cm = 9.807e-5 N·m,
    // 1 mg/cm² = 0.01 kg/m². See ../shared/references/benchmarks.md.
    const char *const kawabata =
      "bending rigidity and areal density: Kawabata KES-FB (Matsudaira et al., J. "
      "Textile Eng. 61(6), 2015); stretch stiffness E*h and Poisson ratio: "
      "Codimensional IPC presets (Li et al., ACM TOG 40(4), 2021)";

    std::vector<std::pair<std::string, std::string>>
    isotropic_fabric(const std::string &stretch_stiffness,
                     const std::string &poisson_ratio,
                     const std::string &areal_density,
                     const std::string &bending_rigidity)
    {
      return {{"Stiffness given as", "E*h"},
              {"Stretch stiffness", stretch_stiffness},
              {"Poisson ratio", poisson_ratio},
              {"Areal density", areal_density},
              {"Bending", "rigidity"},
              {"Bending rigidity", bending_rigidity}};
    }

    // The unit of a Material entry's value, for the documentation.
    std::string
    unit_of(const std::string &entry)
    {
      if (entry == "Stretch stiffness")
        return " N/m";
      if (entry == "Areal density")
        return " kg/m²";
      if (entry == "Bending rigidity")
        return " N·m";
      return "";
    }
  } // namespace


  const std::vector<FabricPreset> &
  fabric_presets()
  {
    // E h = 0.821e6 Pa x 0.318e-3 m = 261.1 N/m; B = 0.118 gf·cm²/cm; W = 12.38 mg/cm².
    // Wool tropical: 96.56 N/m; 0.067; 16.29. Polyester tropical: 120.5 N/m; 0.077;
    // 11.65.
    static const std::vector<FabricPreset> presets = {
      {"cotton",
       isotropic_fabric("261.1", "0.243", "0.1238", "1.157e-5"),
       std::string("cotton broadcloth; ") + kawabata},
      {"wool",
       isotropic_fabric("96.56", "0.277", "0.1629", "6.57e-6"),
       std::string("wool tropical; ") + kawabata},
      {"polyester",
       isotropic_fabric("120.5", "0.381", "0.1165", "7.55e-6"),
       std::string("polyester tropical; ") + kawabata}};
    return presets;
  }


  const FabricPreset *
  find_fabric_preset(const std::string &name)
  {
    for (const FabricPreset &preset : fabric_presets())
      if (preset.name == name)
        return &preset;
    return nullptr;
  }


  std::string
  fabric_preset_names()
  {
    std::string names = "none";
    for (const FabricPreset &preset : fabric_presets())
      names += "|" + preset.name;
    return names;
  }


  std::string
  fabric_preset_documentation()
  {
    std::string text;
    for (const FabricPreset &preset : fabric_presets())
      {
        text += " '" + preset.name + "':";
        for (const auto &[entry, value] : preset.values)
          text += " " + entry + " = " + value + unit_of(entry) + ";";
        text += " (" + preset.source + ").";
      }
    return text;
  }
} // namespace clothsim
