/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "FlowVelocity.H"

namespace iceDEM
{

FlowVelocity::~FlowVelocity() = default;


UniformCurrent::UniformCurrent(const Vec3& current)
:
    current_(current)
{
    if (!current_.allFinite())
    {
        throw Error("drag: the current is not a finite vector", "current");
    }
}


const char* UniformCurrent::name() const
{
    return "empirical";
}


void UniformCurrent::velocity
(
    int,
    const Vec3*,
    int n,
    Vec3* u
) const
{
    for (int k = 0; k < n; ++k)
    {
        u[k] = current_;
    }
}

} // namespace iceDEM
