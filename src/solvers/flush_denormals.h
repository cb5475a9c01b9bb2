#pragma once

// Denormal numbers flushed to zero (x86's MXCSR flags FTZ and DAZ) while an object of
// this class lives, on this thread; restored after. A sparse factorisation of a mesh
// whose mass term screens its stiffness (small time steps) has factor entries that decay
// with the distance in the mesh to below single precision's normal range (1.2e-38), and
// arithmetic on them takes the CPU's slow path: swinging sheet, N = 161, 1e-3 s steps,
// 0.14 to 0.16 s per factorisation flushed against 0.74 to 0.77 s. Flushing such an
// entry changes the factors by less than 1.2e-38 in absolute terms, far below their
// rounding (tangent entries in N/m). Elsewhere than x86: nothing.

#if defined(__SSE2__)
#  include <xmmintrin.h>
#endif

namespace clothsim
{
  class FlushDenormals
  {
  public:
    FlushDenormals()
    {
#if defined(__SSE2__)
      saved = _mm_getcsr();
      _mm_setcsr(saved | flush_to_zero | denormals_are_zero);
#endif
    }
    ~FlushDenormals()
    {
#if defined(__SSE2__)
      _mm_setcsr(saved);
#endif
    }
    FlushDenormals(const FlushDenormals &) = delete;
    FlushDenormals &
    operator=(const FlushDenormals &) = delete;

  private:
#if defined(__SSE2__)
    static constexpr unsigned int flush_to_zero = 0x8000, denormals_are_zero = 0x0040;
    unsigned int                  saved = 0;
#endif
  };
} // namespace clothsim
