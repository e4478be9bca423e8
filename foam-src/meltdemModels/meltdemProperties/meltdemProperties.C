#include "meltdemProperties.H"
#include "physicsTerm.H"

#include <algorithm>

namespace Foam
{
namespace meltdem
{

scalar meltdemProperties::readPositive(const dictionary& d, const word& key, bool allowZero)
{
    if (!d.found(key))
    {
        FatalIOErrorInFunction(d)
            << "missing entry '" << key << "' in " << d.name() << exit(FatalIOError);
    }
    const scalar v = d.get<scalar>(key);
    if (!(allowZero ? v >= 0 : v > 0) || v != v)
    {
        FatalIOErrorInFunction(d)
            << "entry '" << key << "' = " << v << " in " << d.name() << " must be "
            << (allowZero ? "non-negative" : "positive") << exit(FatalIOError);
    }
    return v;
}


void meltdemProperties::checkEntries(const dictionary& d, const wordList& known, const string& what)
{
    for (const word& key : d.toc())
    {
        if (!known.found(key))
        {
            FatalIOErrorInFunction(d)
                << "unknown entry '" << key << "' in " << d.name().c_str()
                << (what.empty() ? "" : " (" + what + ")").c_str() << "; known entries: " << known
                << exit(FatalIOError);
        }
    }
}


meltdemProperties::meltdemProperties(const fvMesh& mesh)
:
    IOdictionary
    (
        IOobject
        (
            "meltdemProperties",
            mesh.time().constant(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    physics_(),
    metal_(),
    gas_(),
    nEnergyCorr_(10),
    energyTolerance_(1e-8),
    maxThermalCo_(1),
    isothermalT_(300)
{
    if (!found("physics"))
    {
        FatalIOErrorInFunction(*this)
            << "missing sub-dictionary 'physics' (the per-term switches)" << exit(FatalIOError);
    }
    const dictionary& ph = subDict("physics");
    // the solver's own switches, and every registered physics term (physicsTerm.H)
    const auto& table = physicsTerm::infoTable();
    // the top level: the solver's own entries and every term's sub-dictionaries, so that a
    // misspelt block (refinment, energyControl) stops instead of switching its part off
    wordList blocks(ownEntries());
    for (const auto& t : table)
    {
        for (const auto& d : t.second.entries)
        {
            if (!blocks.found(word(d.first))) blocks.append(word(d.first));
        }
    }
    checkEntries(*this, blocks);
    wordList known(coreSwitches());
    for (const auto& t : table) known.append(word(t.first));
    for (const word& key : ph.toc())
    {
        if (!known.found(key))
        {
            FatalIOErrorInFunction(ph)
                << "unknown switch '" << key << "' in physics; known switches: " << known
                << exit(FatalIOError);
        }
    }
    // a switch not written is off: a scene names what it needs
    physics_.flow = ph.getOrDefault<bool>("flow", true);
    physics_.energy = ph.getOrDefault<bool>("energy", false);
    physics_.particles = ph.getOrDefault<bool>("particles", false);

    const auto isOn = [&](const std::string& name)
    {
        return name == "flow" ? physics_.flow
             : name == "energy" ? physics_.energy
             : name == "particles" ? physics_.particles
             : ph.getOrDefault<bool>(word(name), false);
    };
    const auto needs = [&ph](bool on, const std::string& term, bool other, const std::string& what)
    {
        if (on && !other)
        {
            FatalIOErrorInFunction(ph)
                << "switch '" << term.c_str() << "' needs '" << what.c_str() << " on'"
                << exit(FatalIOError);
        }
    };
    // the terms switched on, in their order
    std::vector<const physicsTerm::termInfo*> on;
    for (const auto& t : table)
    {
        if (!isOn(t.first)) continue;
        for (const std::string& n : t.second.needs) needs(true, t.first, isOn(n), n);
        on.push_back(&t.second);
    }
    std::stable_sort
    (
        on.begin(), on.end(),
        [](const physicsTerm::termInfo* a, const physicsTerm::termInfo* b) { return a->order < b->order; }
    );
    for (const auto* t : on) terms_.append(word(t->name));

    if (physics_.energy)
    {
        const dictionary& md = modelDict("metal");
        metal_.cp = readPositive(md, "cp");
        metal_.k = readPositive(md, "k");
        metal_.L = readPositive(md, "L", true);
        metal_.Tsolidus = readPositive(md, "Tsolidus");
        metal_.Tliquidus = readPositive(md, "Tliquidus");
        if (!(metal_.Tliquidus > metal_.Tsolidus))
        {
            FatalIOErrorInFunction(md)
                << "Tsolidus (" << metal_.Tsolidus << ") must be below Tliquidus ("
                << metal_.Tliquidus << ") in " << md.name() << exit(FatalIOError);
        }
        const dictionary& gd = modelDict("gas");
        gas_.cp = readPositive(gd, "cp");
        gas_.k = readPositive(gd, "k");

        if (found("energyControls"))
        {
            const dictionary& ec = subDict("energyControls");
            checkEntries(ec, {"nCorrectors", "tolerance", "maxThermalCo"});
            nEnergyCorr_ = ec.getOrDefault<label>("nCorrectors", nEnergyCorr_);
            energyTolerance_ = ec.getOrDefault<scalar>("tolerance", energyTolerance_);
            maxThermalCo_ = ec.getOrDefault<scalar>("maxThermalCo", maxThermalCo_);
            if (nEnergyCorr_ < 1 || energyTolerance_ <= 0 || maxThermalCo_ < 0)
            {
                FatalIOErrorInFunction(ec)
                    << "energyControls: nCorrectors >= 1, tolerance > 0 and"
                       " maxThermalCo >= 0 required"
                    << exit(FatalIOError);
            }
        }
    }
    else
    {
        isothermalT_ = getOrDefault<scalar>("isothermalTemperature", isothermalT_);
        if (!(isothermalT_ > 0))
        {
            FatalIOErrorInFunction(*this)
                << "isothermalTemperature must be > 0 K, not " << isothermalT_ << exit(FatalIOError);
        }
    }
}


const Foam::wordList& meltdemProperties::coreSwitches()
{
    static const wordList names{"flow", "energy", "particles"};
    return names;
}


const Foam::wordList& meltdemProperties::ownEntries()
{
    static const wordList names
    {
        "FoamFile", "physics", "metal", "gas", "energyControls", "isothermalTemperature", "particles",
        "refinement"
    };
    return names;
}


bool meltdemProperties::term(const word& name) const
{
    return terms_.found(name);
}


const dictionary& meltdemProperties::modelDict(const dictionary& properties, const word& name)
{
    if (!properties.found(name) || !properties.isDict(name))
    {
        FatalIOErrorInFunction(properties)
            << "missing sub-dictionary '" << name << "' in " << properties.name()
            << exit(FatalIOError);
    }
    return properties.subDict(name);
}

} // End namespace meltdem
} // End namespace Foam
