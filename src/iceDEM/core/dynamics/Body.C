/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "Body.H"

namespace iceDEM
{

BodyMotion bodyMotionFromName(const std::string& name)
{
    if (name == "free") return BodyMotion::free;
    if (name == "fixed") return BodyMotion::fixed;
    if (name == "prescribed") return BodyMotion::prescribed;
    throw Error
    (
        "unknown motion '" + name + "'; valid: 3(fixed free prescribed)",
        "motion"
    );
}


const char* bodyMotionName(BodyMotion m)
{
    switch (m)
    {
        case BodyMotion::free: return "free";
        case BodyMotion::fixed: return "fixed";
        case BodyMotion::prescribed: return "prescribed";
    }
    return "unknown";
}

} // namespace iceDEM
