#pragma once

// Which kernels the BLAS runs (the dense half of solvers/supernodal_cholesky and of
// MUMPS).
//
// OpenBLAS built for several CPUs (Debian's) picks its kernels by the CPU's model number
// when it loads. A model newer than the library (Intel's Emerald Rapids, family 6 model
// 207, for OpenBLAS 0.3.21) falls back to its 'Prescott' kernels: SSE3, a quarter of the
// vector width of the AVX-512 ones the same CPU runs. On such a CPU the swinging sheet's
// factorisations took 1.3 times as long at N = 81 (27.6 against 20.9 ms each) and 4 times
// at N = 321 (README, "OpenBLAS' kernels").

#include <string>

namespace clothsim
{
  // Call once, first thing in the process, before any BLAS call. Where OpenBLAS is the
  // BLAS, runs its 'Prescott' fallback, OPENBLAS_CORETYPE is unset, and the CPU (and the
  // operating system) supports AVX-512 F/CD/BW/DQ/VL or AVX2 with FMA, re-initialises
  // OpenBLAS with its SkylakeX or Haswell kernels, as OPENBLAS_CORETYPE would. Otherwise
  // changes nothing. Returns whether it changed the kernels.
  bool
  select_blas_kernels();

  // Whether the BLAS runs OpenBLAS' AVX-512 kernels (SkylakeX, Cooperlake or
  // SapphireRapids), chosen by OpenBLAS, OPENBLAS_CORETYPE or select_blas_kernels().
  bool
  avx512_blas_kernels();

  // "OpenBLAS 0.3.21 (SkylakeX kernels)" for the run's provenance, with "chosen by
  // clothsim over OpenBLAS' Prescott" inside the parentheses if `selected`, or
  // "OPENBLAS_CORETYPE=<value>" if the environment chose them; "BLAS: not OpenBLAS" when
  // the BLAS loaded is another library.
  std::string
  blas_description(const bool selected);
} // namespace clothsim
