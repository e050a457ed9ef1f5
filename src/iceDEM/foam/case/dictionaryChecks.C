/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "dictionaryChecks.H"
#include "error.H"
#include "SortableList.H"

// * * * * * * * * * * * * * * * * Functions * * * * * * * * * * * * * * * //

void Foam::iceDEMChecks::checkKeywords
(
    const dictionary& dict,
    std::initializer_list<const char*> allowed,
    const string& what
)
{
    for (const entry& e : dict)
    {
        const word& key = e.keyword();
        if (key.empty() || key[0] == '_')
        {
            continue;
        }
        bool found = false;
        for (const char* a : allowed)
        {
            if (key == a)
            {
                found = true;
                break;
            }
        }
        if (!found)
        {
            wordList valid(allowed.size());
            label i = 0;
            for (const char* a : allowed)
            {
                valid[i++] = a;
            }
            FatalIOErrorInFunction(dict)
                << "Unknown entry '" << key << "' in " << what.c_str() << nl
                << "    Valid entries: " << flatOutput(valid) << nl
                << "    (entries starting with '_' are free for the user's"
                << " own $variables)" << nl
                << exit(FatalIOError);
        }
    }
}


Foam::scalar Foam::iceDEMChecks::positive
(
    const dictionary& dict,
    const word& key
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(v > 0) || !std::isfinite(v))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << v
            << ": it must be a finite number > 0" << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::iceDEMChecks::positive
(
    const dictionary& dict,
    const word& key,
    scalar deflt
)
{
    return dict.found(key, keyType::LITERAL) ? positive(dict, key) : deflt;
}


Foam::scalar Foam::iceDEMChecks::nonNegative
(
    const dictionary& dict,
    const word& key,
    scalar deflt
)
{
    const scalar v = dict.getOrDefault<scalar>(key, deflt);
    if (!(v >= 0) || !std::isfinite(v))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << v
            << ": it must be a finite number >= 0" << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::iceDEMChecks::inRange
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(v >= lo && v <= hi))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << v
            << ": it must lie in [" << lo << ", " << hi << "]" << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::iceDEMChecks::inRange
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi,
    scalar deflt
)
{
    return
        dict.found(key, keyType::LITERAL)
      ? inRange(dict, key, lo, hi)
      : deflt;
}


Foam::label Foam::iceDEMChecks::labelInRange
(
    const dictionary& dict,
    const word& key,
    label lo,
    label hi,
    label deflt
)
{
    const label v = dict.getOrDefault<label>(key, deflt);
    if (v < lo || v > hi)
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << v
            << ": it must be an integer in [" << lo << ", " << hi << "]"
            << nl << exit(FatalIOError);
    }
    return v;
}


Foam::word Foam::iceDEMChecks::selectName
(
    const dictionary& dict,
    const word& key,
    const wordList& valid,
    const word& deflt
)
{
    const word name =
        deflt.empty()
      ? dict.get<word>(key)
      : dict.getOrDefault<word>(key, deflt);

    if (!valid.found(name))
    {
        SortableList<word> sorted(valid);
        FatalIOErrorInFunction(dict)
            << "Unknown " << key << " '" << name << "'" << nl << nl
            << "Valid choices of " << key << " :" << nl
            << sorted.size() << nl << '(' << nl;
        for (const word& w : sorted)
        {
            FatalIOError << "    " << w << nl;
        }
        FatalIOError << ')' << nl << exit(FatalIOError);
    }
    return name;
}


Foam::vector Foam::iceDEMChecks::unitVector
(
    const dictionary& dict,
    const word& key
)
{
    const vector v = dict.get<vector>(key);
    const scalar m = mag(v);
    if (!(m > VSMALL) || !std::isfinite(m))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << v
            << ": it must be a finite non-zero vector" << nl
            << exit(FatalIOError);
    }
    return v/m;
}


Foam::tensor Foam::iceDEMChecks::rotationTensor
(
    const dictionary& dict,
    const word& key
)
{
    const tensor R = dict.getOrDefault<tensor>(key, tensor::I);
    const scalar orth = mag((R & R.T()) - tensor::I);
    if (!(orth < 1e-6) || !(mag(det(R) - 1) < 1e-6))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << R
            << ": it must be a rotation tensor (orthonormal rows, det +1;"
            << " R & R.T() - I has norm " << orth << ", det " << det(R)
            << ")" << nl
            << exit(FatalIOError);
    }
    return R;
}


void Foam::iceDEMChecks::coreError
(
    const dictionary& dict,
    const std::exception& err,
    const string& context
)
{
    const ::iceDEM::Error* ice = dynamic_cast<const ::iceDEM::Error*>(&err);

    FatalIOErrorInFunction(dict) << context.c_str();
    if (ice && !ice->entry().empty())
    {
        FatalIOError << ": entry '" << ice->entry().c_str() << "'";
    }
    FatalIOError
        << nl << "    " << err.what() << nl
        << exit(FatalIOError);

    // exit() does not return; keeps [[noreturn]] honest if it throws
    std::abort();
}


// ************************************************************************* //
