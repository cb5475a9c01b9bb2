// Benchmark (not a ctest test: it asserts nothing and prints timings): the cost per call
// of the element kernels that a Newton iteration evaluates once per triangle, the
// membrane's (physics/membrane.h) and the bending's (physics/bending.h), on 4,096
// triangles of the swinging sheet's N = 81 size (right triangles of legs 1/80 m, each
// vertex moved by up to 2 mm, each edge angle up to 0.02 rad; cotton: E·h = 1,200 N/m,
// ν = 0.42, D = 1e-5 N·m). Each kernel is timed over `passes` passes of `calls` calls;
// the fastest pass is reported, since on a shared machine the others only add noise.
// Compare two builds by running their benchmarks one after the other, more than once.
//
//   build/tests/kernel_benchmark [calls per pass, default 2,000,000] [passes, default 5]

#include "physics/bending.h"
#include "physics/membrane.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace clothsim::physics;

int
main(int argc, char **argv)
{
  const long calls  = argc > 1 ? std::atol(argv[1]) : 2000000;
  const int  passes = argc > 2 ? std::atoi(argv[2]) : 5;
  if (calls < 4096 || passes < 1)
    {
      std::cerr << "usage: kernel_benchmark [calls per pass >= 4096] [passes >= 1]\n";
      return 2;
    }

  constexpr unsigned int                 n_triangles = 4096;
  const double                           side        = 1. / 80.;
  std::mt19937                           generator(2026);
  std::uniform_real_distribution<double> move(-0.002, 0.002), turn(-0.02, 0.02);
  const BendingMaterial                  bending{1e-5, 0.42, DirectorFunction::angle};
  const MembraneMaterial                 membrane{1200., 0.42};

  std::vector<TrianglePositions> reference(n_triangles), current(n_triangles);
  std::vector<EdgeDirectors>     directors(n_triangles);
  std::vector<EdgeAngles>        psi(n_triangles);
  std::vector<BendingRestData>   bending_rest(n_triangles);
  std::vector<MembraneRestData>  membrane_rest(n_triangles);
  std::vector<MembraneStiffness> stiffness(n_triangles);
  for (unsigned int e = 0; e < n_triangles; ++e)
    {
      reference[e] = {{Point<3>(0, 0, 0), Point<3>(side, 0, 0), Point<3>(0, side, 0)}};
      current[e]   = reference[e];
      for (Point<3> &x : current[e])
        for (unsigned int c = 0; c < 3; ++c)
          x[c] += move(generator);
      for (unsigned int i = 0; i < 3; ++i)
        {
          directors[e].reference[i] = Tensor<1, 3>({0., 0., 1.});
          directors[e].sign[i]      = i == 1 ? -1. : 1.;
          psi[e][i]                 = turn(generator);
        }
      bending_rest[e]  = bending_rest_data(bending, reference[e], directors[e]);
      membrane_rest[e] = membrane_rest_data(reference[e]);
      stiffness[e]     = membrane_stiffness(membrane, reference[e], membrane_rest[e]);
    }

  std::cout << "element kernels, " << calls << " calls per pass, fastest of " << passes
            << " passes\n";
  // Prints the fastest pass's mean time per call (ns); `sink` keeps the results alive.
  // (A template, not std::function: an indirect call would add to the small kernels.)
  double     sink   = 0.;
  const auto report = [&](const std::string &name, const auto &kernel) {
    double best = std::numeric_limits<double>::infinity();
    for (int pass = 0; pass < passes; ++pass)
      {
        const auto start = std::chrono::steady_clock::now();
        for (long k = 0; k < calls; ++k)
          sink += kernel(static_cast<unsigned int>(k % n_triangles));
        const std::chrono::duration<double, std::nano> elapsed =
          std::chrono::steady_clock::now() - start;
        best = std::min(best, elapsed.count() / static_cast<double>(calls));
      }
    std::cout << "  " << std::left << std::setw(34) << name << std::right << std::setw(9)
              << std::fixed << std::setprecision(1) << best << " ns per call\n";
  };

  BendingVector bending_gradient;
  BendingMatrix bending_hessian;
  ElementVector membrane_gradient;
  ElementMatrix membrane_hessian;
  const double  no_floor = 0.;
  report("membrane energy", [&](unsigned int e) {
    return membrane_energy(stiffness[e], membrane_rest[e], current[e]);
  });
  report("membrane gradient", [&](unsigned int e) {
    return membrane_energy_gradient_hessian(
      stiffness[e], membrane_rest[e], current[e], no_floor, membrane_gradient, nullptr);
  });
  report("membrane Hessian (mixed stress)", [&](unsigned int e) {
    return membrane_energy_gradient_hessian(stiffness[e],
                                            membrane_rest[e],
                                            current[e],
                                            no_floor,
                                            membrane_gradient,
                                            &membrane_hessian,
                                            &reference[e]) +
           membrane_hessian[2][5];
  });
  report("bending energy", [&](unsigned int e) {
    return bending_energy(bending, bending_rest[e], current[e], directors[e], psi[e]);
  });
  // The bending kernel with a Gauss-Newton or exact Hessian, or without one.
  const auto bending_call =
    [&](unsigned int e, bool gauss_newton, BendingMatrix *hessian) {
      const double energy = bending_energy_gradient_hessian(bending,
                                                            bending_rest[e],
                                                            current[e],
                                                            directors[e],
                                                            psi[e],
                                                            gauss_newton,
                                                            bending_gradient,
                                                            hessian);
      return hessian != nullptr ? energy + (*hessian)[3][10] : energy;
    };
  report("bending gradient",
         [&](unsigned int e) { return bending_call(e, true, nullptr); });
  report("bending Gauss-Newton Hessian",
         [&](unsigned int e) { return bending_call(e, true, &bending_hessian); });
  report("bending exact Hessian",
         [&](unsigned int e) { return bending_call(e, false, &bending_hessian); });
  // Printed so that no kernel is optimised away.
  std::cout << "  (checksum " << std::scientific << std::setprecision(3) << sink << ")\n";
  return 0;
}
