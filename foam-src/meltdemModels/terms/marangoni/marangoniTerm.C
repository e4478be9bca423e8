#include "marangoniTerm.H"

#include "fvMatrices.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(marangoniTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::marangoniTerm::info()
{
    return {"marangoni", 30, {"energy", "surfaceTension"}, {}, "tangential Marangoni force", {"momentum"}};
}


Foam::meltdem::marangoniTerm::marangoniTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    forces_(mesh, meltdemProperties::modelDict(properties, "surfaceTension"))
{}


void Foam::meltdem::marangoniTerm::addMomentum(fvVectorMatrix& UEqn, const solverFields& f) const
{
    UEqn -= forces_.marangoniForce(f.alpha1, f.T, f.liquidFraction, f.rho1, f.rho2);
}
