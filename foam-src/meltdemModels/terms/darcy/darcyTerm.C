#include "darcyTerm.H"

#include "fvMatrices.H"
#include "fvmSup.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(darcyTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::darcyTerm::info()
{
    return {"darcy", 10, {"energy", "flow"}, {{"darcy", {{"C", "> 0"}, {"b", "> 0"}}}},
            "Carman-Kozeny sink of solid and mushy metal", {"momentum"}};
}


Foam::meltdem::darcyTerm::darcyTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    C_("darcyC", dimDensity/dimTime, 0),
    b_(1)
{
    const dictionary& d = meltdemProperties::modelDict(properties, "darcy");
    C_.value() = meltdemProperties::readPositive(d, "C");
    b_ = meltdemProperties::readPositive(d, "b");
}


void Foam::meltdem::darcyTerm::addMomentum(fvVectorMatrix& UEqn, const solverFields& f) const
{
    // Carman-Kozeny: C (1 - f)^2 / (f^3 + b), in the metal only
    UEqn += fvm::Sp
    (
        f.alpha1*C_*sqr(1 - f.liquidFraction)/(pow3(f.liquidFraction) + b_),
        UEqn.psi()
    );
}
