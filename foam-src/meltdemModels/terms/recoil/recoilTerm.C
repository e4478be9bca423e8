#include "recoilTerm.H"
#include "evaporationTerm.H"

#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(recoilTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::recoilTerm::info()
{
    return {"recoil", 40, {"energy", "flow"}, {{"evaporation", evaporationTerm::entries()}},
            "recoil pressure of the evaporating metal", {"momentum"}};
}


Foam::meltdem::recoilTerm::recoilTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    model_(mesh, meltdemProperties::modelDict(properties, "evaporation"))
{}


Foam::tmp<Foam::volScalarField> Foam::meltdem::recoilTerm::surfacePressure
(
    const volScalarField& T
) const
{
    return model_.recoilPressure(T);
}
