#include "laserTerm.H"

#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(laserTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::laserTerm::info()
{
    return {"laser", 50, {"energy"},
            {{"laser", {{"power", ">= 0"}, {"absorptivity", ">= 0"}, {"radius", "> 0"}}}},
            "Gaussian laser absorbed at the metal interface", {"energy"}};
}


Foam::meltdem::laserTerm::laserTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    laser_(mesh, meltdemProperties::modelDict(properties, "laser"))
{}


Foam::tmp<Foam::volScalarField> Foam::meltdem::laserTerm::heatSource
(
    const volScalarField& alpha1
) const
{
    tmp<volScalarField> q(laser_.heatSource(alpha1));
    Info<< "Laser: absorbed power " << laser_.absorbedPower() << " W" << endl;
    return q;
}
