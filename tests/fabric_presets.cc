// Fabric presets (io/fabric_presets.h): each produces exactly its documented values,
// those values follow from the published measurements in their units (Kawabata: 1
// gf·cm²/cm = 9.807e-5 N·m, 1 mg/cm² = 0.01 kg/m²; E h from E and h), and an entry set in
// the file or with --set overrides the preset while the others stay.

#include <deal.II/base/parameter_handler.h>

#include "io/parameters.h"
#include "test_checks.h"

#include <algorithm>
#include <cmath>

using namespace clothsim;
using namespace clothsim::test;

namespace
{
  struct Documented
  {
    std::string name;
    double      stretch_stiffness, poisson_ratio, areal_density, bending_rigidity;
    // The published measurements: E (Pa), h (m), B (gf·cm²/cm), W (mg/cm²).
    double young, thickness, kawabata_b, kawabata_w;
  };

  MaterialParameters
  read(const std::vector<std::string> &overrides)
  {
    ParameterHandler prm;
    return read_parameters(prm, source_path("tests/scenes/fabric_preset.prm"), overrides)
      .parameters.material;
  }
} // namespace

int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &pcout = env.pcout;

  const std::vector<Documented> presets = {
    {"cotton", 261.1, 0.243, 0.1238, 1.157e-5, 0.821e6, 0.318e-3, 0.118, 12.38},
    {"wool", 96.56, 0.277, 0.1629, 6.57e-6, 0.170e6, 0.568e-3, 0.067, 16.29},
    {"polyester", 120.5, 0.381, 0.1165, 7.55e-6, 0.478e6, 0.252e-3, 0.077, 11.65}};

  for (const Documented &fabric : presets)
    {
      const MaterialParameters m = read({"Material/Preset=" + fabric.name});
      check(pcout,
            m.stretch_stiffness == fabric.stretch_stiffness &&
              m.poisson_ratio == fabric.poisson_ratio &&
              m.areal_density == fabric.areal_density &&
              m.bending_rigidity == fabric.bending_rigidity && m.bending &&
              !m.orthotropic && m.preset == fabric.name,
            fabric.name + ": exactly the documented stretch stiffness, Poisson ratio, "
                          "areal density and bending rigidity, isotropic, with bending");
      // The documented values are the measurements converted and rounded to 4 digits.
      check_below(pcout,
                  fabric.name + ": E h against E x h, relative",
                  std::abs(fabric.stretch_stiffness - fabric.young * fabric.thickness) /
                    fabric.stretch_stiffness,
                  5e-4);
      check_below(pcout,
                  fabric.name + ": D against B x 9.807e-5 N·m, relative",
                  std::abs(fabric.bending_rigidity - fabric.kawabata_b * 9.807e-5) /
                    fabric.bending_rigidity,
                  5e-4);
      check_below(pcout,
                  fabric.name + ": areal density against W x 0.01 kg/m², relative",
                  std::abs(fabric.areal_density - fabric.kawabata_w * 0.01) /
                    fabric.areal_density,
                  1e-12);
    }

  // Denim (orthotropic): exactly the documented values, which follow from Wang et al.'s
  // small-strain stretching row (C_uu, C_uv, C_vv, C_s) and zero-curvature bending
  // samples as ARCSim reads them (io/fabric_presets.cc): c = 2 C, warp along v.
  {
    const MaterialParameters m = read({"Material/Preset=denim"});
    check(pcout,
          m.orthotropic && m.stretch_stiffness == 2027. &&
            m.weft_stretch_stiffness == 410.5 && m.shear_stiffness == 53.39 &&
            m.poisson_ratio == 0.04984 && m.areal_density == 0.324 && m.bending &&
            m.bending_rigidity == 6.420e-5 && m.weft_bending_rigidity == 9.695e-5,
          "denim: exactly the documented orthotropic values (2027, 410.5, 53.39 N/m, "
          "nu_12 0.04984, 0.324 kg/m², 6.420e-5 and 9.695e-5 N·m)");
    const double c_uu = 2 * 205.352005, c_uv = 2 * 10.234077, c_vv = 2 * 1013.88629,
                 c_s      = 53.387184;
    const double d        = 1. - c_uv * c_uv / (c_vv * c_uu);
    const auto   relative = [](const double value, const double exact) {
      return std::abs(value - exact) / exact;
    };
    check_below(pcout,
                "denim: largest relative difference of k_1, k_2, g, nu_12, D_1, D_2 "
                "from the data",
                std::max({relative(m.stretch_stiffness, c_vv * d),
                          relative(m.weft_stretch_stiffness, c_uu * d),
                          relative(m.shear_stiffness, c_s),
                          relative(m.poisson_ratio, c_uv / c_uu),
                          relative(m.bending_rigidity, 64.196457e-6),
                          relative(m.weft_bending_rigidity, 96.951576e-6)}),
                5e-4);
    const MaterialParameters along_y =
      read({"Material/Preset=denim", "Material/Warp direction=0, 1, 0"});
    check(pcout,
          along_y.warp_direction[1] == 1. && along_y.warp_direction[0] == 0. &&
            along_y.stretch_stiffness == 2027. && along_y.orthotropic,
          "denim with its warp along y: the rest denim");
  }

  // Overrides: one entry changes, the preset's others stay; "none" keeps the defaults.
  const MaterialParameters stiffer = read({"Material/Bending rigidity=2e-5"});
  check(pcout,
        stiffer.bending_rigidity == 2e-5 && stiffer.stretch_stiffness == 261.1 &&
          stiffer.areal_density == 0.1238,
        "cotton with --set 'Bending rigidity=2e-5': D = 2e-5 N·m, the rest cotton");
  const MaterialParameters limp =
    read({"Material/Preset=wool", "Material/Bending=none", "Material/Poisson ratio=0.1"});
  check(pcout,
        !limp.bending && limp.poisson_ratio == 0.1 && limp.stretch_stiffness == 96.56 &&
          limp.areal_density == 0.1629,
        "wool without bending and with nu = 0.1: the rest wool");
  const MaterialParameters none = read({"Material/Preset=none"});
  check(pcout,
        none.stretch_stiffness == 100. && none.poisson_ratio == 0.3 &&
          none.areal_density == 0.1 && !none.bending,
        "preset none: the declared defaults (100 N/m, 0.3, 0.1 kg/m², no bending)");

  return finish_tally(pcout);
}
