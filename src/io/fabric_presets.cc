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

    // Wang, O'Brien & Ramamoorthi, "Data-driven elastic models for cloth", ACM TOG
    // 30(4), 2011: 11 oz black denim (99 % cotton, 1 % spandex), as distributed with
    // ARCSim (Narain, Samii & O'Brien 2012; materials/11oz-black-denim.json), read as
    // ARCSim reads it. Stretching: the small-strain row (C_uu, C_uv, C_vv, C_s) =
    // (205.352, 10.2341, 1013.89, 53.3872) N/m gives the energy density W = C_uu E_uu² +
    // 2 C_uv E_uu E_vv + C_vv E_vv² + 2 C_s E_uv² of the Green strain E (ARCSim doubles
    // the row into ½ k E²), so physics/sheet_stiffness.h's c_11 = 2 C_vv, c_22 = 2 C_uu,
    // c_12 = 2 C_uv, c_66 = C_s, with the warp along v, the stiffer axis (the source
    // names no yarn directions; stretch denim has its elastane in the weft); then ν_12 =
    // c_12/c_22, d = 1 − c_12²/(c_11 c_22), k_1 = c_11 d, k_2 = c_22 d. Bending: the
    // zero-curvature samples, in N·m, for folds along u (64.196e-6: curvature along v,
    // the warp) and along v (96.952e-6).
    const char *const wang_2011 =
      "11 oz black denim measured by Wang, O'Brien & Ramamoorthi (ACM TOG 30(4), 2011), "
      "small-strain stretching and zero-curvature bending as ARCSim reads them, warp = "
      "the stiffer axis";

    // The unit of a Material entry's value, for the documentation.
    std::string
    unit_of(const std::string &entry)
    {
      if (entry == "Stretch stiffness" || entry == "Weft stretch stiffness" ||
          entry == "Shear stiffness")
        return " N/m";
      if (entry == "Areal density")
        return " kg/m²";
      if (entry == "Bending rigidity" || entry == "Weft bending rigidity")
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
       std::string("polyester tropical; ") + kawabata},
      {"denim",
       {{"Anisotropy", "orthotropic"},
        {"Stiffness given as", "E*h"},
        {"Stretch stiffness", "2027"},
        {"Weft stretch stiffness", "410.5"},
        {"Shear stiffness", "53.39"},
        {"Poisson ratio", "0.04984"},
        {"Areal density", "0.324"},
        {"Bending", "rigidity"},
        {"Bending rigidity", "6.420e-5"},
        {"Weft bending rigidity", "9.695e-5"}},
       wang_2011}};
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
