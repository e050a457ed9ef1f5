/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.

    This program is free software: you can redistribute it and/or modify it
    under the terms of the GNU General Public License as published by the
    Free Software Foundation, either version 3 of the License, or (at your
    option) any later version. See <http://www.gnu.org/licenses/>.
\*---------------------------------------------------------------------------*/

#include "timeRegistry.H"
#include "IOField.H"

// * * * * * * * * * * * * * * * * Functions  * * * * * * * * * * * * * * * //

void Foam::storeOnTime
(
    const Time& runTime,
    const word& key,
    const scalarField& values
)
{
    if (runTime.foundObject<IOField<scalar>>(key))
    {
        runTime.lookupObjectRef<IOField<scalar>>(key) = values;
        return;
    }
    IOField<scalar>* reg = new IOField<scalar>
    (
        IOobject
        (
            key,
            runTime.timeName(),
            runTime,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            true
        ),
        values
    );
    reg->store();
}


// ************************************************************************* //
