/*---------------------------------------------------------------------------*\
    iceDEM tests: trap floating-point errors as OpenFOAM does (FOAM_SIGFPE),
    so that a division by zero or an overflow in the core fails a unit test
    instead of crashing a solver later.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include <cfenv>

namespace
{
    const int trapsEnabled = feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
}
