#include "meltdemProperties.H"

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
    darcyC_(0),
    darcyB_(1),
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
    const wordList known
    {
        "flow", "energy", "darcy", "surfaceTension", "marangoni", "recoil", "laser",
        "evaporation", "buoyancy", "particles"
    };
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
    physics_.darcy = ph.getOrDefault<bool>("darcy", false);
    physics_.surfaceTension = ph.getOrDefault<bool>("surfaceTension", false);
    physics_.marangoni = ph.getOrDefault<bool>("marangoni", false);
    physics_.recoil = ph.getOrDefault<bool>("recoil", false);
    physics_.laser = ph.getOrDefault<bool>("laser", false);
    physics_.evaporation = ph.getOrDefault<bool>("evaporation", false);
    physics_.buoyancy = ph.getOrDefault<bool>("buoyancy", false);
    physics_.particles = ph.getOrDefault<bool>("particles", false);

    const auto needs = [&ph](bool on, const char* term, bool other, const char* what)
    {
        if (on && !other)
        {
            FatalIOErrorInFunction(ph)
                << "switch '" << term << "' needs '" << what << " on'" << exit(FatalIOError);
        }
    };
    needs(physics_.marangoni, "marangoni", physics_.energy, "energy");
    needs(physics_.marangoni, "marangoni", physics_.surfaceTension, "surfaceTension");
    needs(physics_.recoil, "recoil", physics_.energy, "energy");
    needs(physics_.recoil, "recoil", physics_.flow, "flow");
    needs(physics_.laser, "laser", physics_.energy, "energy");
    needs(physics_.evaporation, "evaporation", physics_.energy, "energy");
    needs(physics_.buoyancy, "buoyancy", physics_.energy, "energy");
    needs(physics_.darcy, "darcy", physics_.energy, "energy");
    needs(physics_.darcy, "darcy", physics_.flow, "flow");
    needs(physics_.surfaceTension, "surfaceTension", physics_.flow, "flow");
    needs(physics_.particles, "particles", physics_.flow, "flow");

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
        metal_.beta = 0;
        metal_.Tref = 0;
        if (physics_.buoyancy)
        {
            metal_.beta = readPositive(md, "beta", true);
            metal_.Tref = readPositive(md, "Tref");
        }
        const dictionary& gd = modelDict("gas");
        gas_.cp = readPositive(gd, "cp");
        gas_.k = readPositive(gd, "k");

        if (found("energyControls"))
        {
            const dictionary& ec = subDict("energyControls");
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
    }
    if (physics_.darcy)
    {
        const dictionary& dd = modelDict("darcy");
        darcyC_ = readPositive(dd, "C");
        darcyB_ = readPositive(dd, "b");
    }
}


const dictionary& meltdemProperties::modelDict(const word& name) const
{
    if (!found(name) || !isDict(name))
    {
        FatalIOErrorInFunction(*this)
            << "missing sub-dictionary '" << name << "' in " << this->name()
            << exit(FatalIOError);
    }
    return subDict(name);
}

} // End namespace meltdem
} // End namespace Foam
