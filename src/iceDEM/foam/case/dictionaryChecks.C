/*---------------------------------------------------------------------------*\
    iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
    Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
\*---------------------------------------------------------------------------*/

#include "dictionaryChecks.H"
#include "error.H"
#include "SortableList.H"
#include "IFstream.H"
#include "DynamicList.H"
#include "HashTable.H"
#include "token.H"
#include "Switch.H"

#include <cstring>

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
    // A rotation's components lie in [-1, 1]: checked first, so that the
    // products below cannot overflow
    bool bounded = true;
    for (direction i = 0; i < tensor::nComponents; ++i)
    {
        bounded = bounded && std::abs(R[i]) <= 1 + 1e-6;
    }
    const scalar orth = bounded ? mag((R & R.T()) - tensor::I) : GREAT;
    if (!bounded || !(orth < 1e-6) || !(mag(det(R) - 1) < 1e-6))
    {
        FatalIOErrorInFunction(dict)
            << "Entry '" << key << "' is " << R
            << ": it must be a rotation tensor (orthonormal rows, det +1;";
        if (bounded)
        {
            FatalIOError
                << " R & R.T() - I has norm " << orth << ", det " << det(R);
        }
        else
        {
            FatalIOError << " a component is outside [-1, 1]";
        }
        FatalIOError
            << ")" << nl
            << exit(FatalIOError);
    }
    return R;
}


void Foam::iceDEMChecks::checkDuplicateKeywords
(
    const dictionary& dict,
    const fileName& file
)
{
    IFstream is(file);
    if (!is.good())
    {
        return;     // the reader has said what is wrong with the file
    }

    // Keywords seen (with their line) in every open dictionary
    DynamicList<HashTable<label, word>> scopes(1);
    DynamicList<word> scopeNames(1);
    scopes.append(HashTable<label, word>());
    scopeNames.append("the top level");

    auto isPunct = [](const token& t, const char c)
    {
        return t.isPunctuation() && t.pToken() == c;
    };

    token t;
    while (is.read(t).good() && !t.undefined())
    {
        if (isPunct(t, token::END_BLOCK))
        {
            if (scopes.size() > 1)
            {
                scopes.remove();
                scopeNames.remove();
            }
            continue;
        }
        if (!t.isWord() && !t.isString())
        {
            continue;
        }
        const word key(t.isWord() ? t.wordToken() : word(t.stringToken(), false));
        const label line = t.lineNumber();

        // Directives (#include "file", #inputMode merge, ...) and $macros:
        // skip their argument
        if (key.size() && (key[0] == '#' || key[0] == '$'))
        {
            if (key[0] == '#')
            {
                is.read(t);
            }
            continue;
        }

        auto iter = scopes.last().find(key);
        if (iter.found())
        {
            FatalIOErrorInFunction(dict)
                << "Entry '" << key << "' is given twice in "
                << scopeNames.last() << " of " << file << " (lines "
                << iter.val() << " and " << line << "): the second would"
                << " silently merge into the first. Give every entry a"
                << " name of its own." << nl
                << exit(FatalIOError);
        }
        scopes.last().insert(key, line);

        // The value: a dictionary, or tokens up to ';' (lists may hold
        // dictionaries)
        if (!is.read(t).good())
        {
            break;
        }
        if (isPunct(t, token::BEGIN_BLOCK))
        {
            scopes.append(HashTable<label, word>());
            scopeNames.append("'" + key + "'");
            continue;
        }
        label depth = 0;
        while (true)
        {
            if
            (
                isPunct(t, token::BEGIN_LIST) || isPunct(t, token::BEGIN_BLOCK)
             || isPunct(t, token::BEGIN_SQR)
            )
            {
                ++depth;
            }
            else if
            (
                isPunct(t, token::END_LIST) || isPunct(t, token::END_BLOCK)
             || isPunct(t, token::END_SQR)
            )
            {
                --depth;
            }
            else if (depth <= 0 && isPunct(t, token::END_STATEMENT))
            {
                break;
            }
            if (!is.read(t).good() || t.undefined())
            {
                return;
            }
        }
    }
}


namespace
{

//- The '|' separated names of a listed range
Foam::wordList listedNames(const char* file, const char* dict, const char* key)
{
    using namespace Foam;
    for (const iceDEMChecks::caseEntry& c : iceDEMChecks::caseEntries())
    {
        if
        (
            std::strcmp(c.file, file) == 0
         && std::strcmp(c.dictionary, dict) == 0
         && std::strcmp(c.keyword, key) == 0
        )
        {
            wordList names;
            std::string r(c.range);
            std::size_t b = 0;
            for (std::size_t e; (e = r.find('|', b)) != std::string::npos; b = e + 1)
            {
                names.append(word(r.substr(b, e - b)));
            }
            names.append(word(r.substr(b)));
            return names;
        }
    }
    return wordList();
}


//- OpenFOAM's entries of iceDEM's function objects that OpenFOAM reads
//  before the object exists (executeControl, writeControl: its error names
//  the file only) or never checks (log, region): checked here, by name,
//  before the function objects start
void checkFunctionObjectControls(const Foam::dictionary& cd)
{
    using namespace Foam;
    const dictionary* fptr = cd.findDict("functions", keyType::LITERAL);
    if (!fptr)
    {
        return;
    }
    const char* file = "system/controlDict";
    for (const entry& fe : *fptr)
    {
        if (!fe.isDict())
        {
            continue;
        }
        const word type(fe.dict().getOrDefault<word>("type", word::null));
        if (type != "iceLoadStatistics" && type != "iceClearance")
        {
            continue;
        }
        const std::string whereText("functions/*(type " + type + ")");
        const char* where = whereText.c_str();
        const dictionary& d = fe.dict();
        for (const char* key : {"executeControl", "writeControl"})
        {
            if (!d.found(key, keyType::LITERAL))
            {
                continue;
            }
            const wordList valid(listedNames(file, where, key));
            ITstream& is = d.lookup(key, keyType::LITERAL);
            const token t(is.size() == 1 ? is[0] : token());
            if (!t.isWord() || !valid.found(t.wordToken()))
            {
                FatalIOErrorInFunction(d)
                    << "Entry '" << key << "' of function object "
                    << fe.keyword() << " in " << file << " is " << is
                    << ": valid are " << flatOutput(valid) << nl
                    << exit(FatalIOError);
            }
        }
        if (d.found("log", keyType::LITERAL))
        {
            ITstream& is = d.lookup("log", keyType::LITERAL);
            const token t(is.size() == 1 ? is[0] : token());
            if (!t.isWord() || !Switch(t.wordToken(), true).valid())
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'log' of function object " << fe.keyword()
                    << " in " << file << " is " << is << ": a switch"
                    << " (true/false, on/off, yes/no) is expected" << nl
                    << exit(FatalIOError);
            }
        }
        if (d.found("region", keyType::LITERAL))
        {
            ITstream& is = d.lookup("region", keyType::LITERAL);
            if (is.size() != 1 || !is[0].isWord())
            {
                FatalIOErrorInFunction(d)
                    << "Entry 'region' of function object " << fe.keyword()
                    << " in " << file << " is " << is << ": a mesh region"
                    << " name is expected" << nl << exit(FatalIOError);
            }
        }
    }
}

} // End anonymous namespace


void Foam::iceDEMChecks::checkTimeControls(const Time& runTime)
{
    const dictionary& cd = runTime.controlDict();
    checkFunctionObjectControls(cd);

    const scalar dt = cd.get<scalar>("deltaT");
    if (!(dt > 0) || !std::isfinite(dt))
    {
        FatalIOErrorInFunction(cd)
            << "Entry 'deltaT' is " << dt << ": the time step must be a"
            << " finite number > 0 (a zero or negative step never reaches"
            << " endTime)" << nl
            << exit(FatalIOError);
    }

    const scalar start = runTime.startTime().value();
    const scalar end = runTime.endTime().value();
    if (!std::isfinite(end))
    {
        FatalIOErrorInFunction(cd)
            << "Entry 'endTime' is " << end << ": it must be a finite time"
            << nl << exit(FatalIOError);
    }
    // Half a step of slack: the time names are rounded
    if (end < start - 0.5*dt)
    {
        FatalIOErrorInFunction(cd)
            << "Entry 'endTime' (" << end << ") is before the start time "
            << start << " (startFrom "
            << cd.getOrDefault<word>("startFrom", "startTime")
            << "): nothing would run" << nl
            << exit(FatalIOError);
    }
    if (end < start + 0.5*dt)
    {
        IOWarningInFunction(cd)
            << "Entry 'endTime' (" << end << ") is the start time " << start
            << ": no step is run" << nl << endl;
    }
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
