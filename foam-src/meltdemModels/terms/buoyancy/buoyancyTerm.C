#include "buoyancyTerm.H"

#include "fvMatrices.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(buoyancyTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::buoyancyTerm::info()
{
    return {"buoyancy", 70, {"energy"}, {{"metal", {{"beta", ">= 0"}, {"Tref", "> 0"}}}},
            "Boussinesq buoyancy of the metal", {"momentum"}};
}


Foam::meltdem::buoyancyTerm::buoyancyTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    beta_("betaMetal", dimless/dimTemperature, 0),
    Tref_("Tref", dimTemperature, 0)
{
    const dictionary& md = meltdemProperties::modelDict(properties, "metal");
    beta_.value() = meltdemProperties::readPositive(md, "beta", true);
    Tref_.value() = meltdemProperties::readPositive(md, "Tref");
}


void Foam::meltdem::buoyancyTerm::addMomentum(fvVectorMatrix& UEqn, const solverFields& f) const
{
    // Boussinesq: the metal's density falls by beta (T - Tref)
    UEqn += f.alpha1*f.rho1*beta_*(f.T - Tref_)*f.g;
}
