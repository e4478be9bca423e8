#include "evaporationTerm.H"

#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(evaporationTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::evaporationTerm::info()
{
    return {"evaporation", 60, {"energy"}, {{"evaporation", evaporationTerm::entries()}},
            "evaporation heat loss of the metal surface", {"energy"}};
}


std::vector<Foam::meltdem::physicsTerm::entrySpec> Foam::meltdem::evaporationTerm::entries()
{
    return {{"pAmbient", ""}, {"CT", ""}, {"Tboil", ""}, {"hv", ""}, {"cp", ""}, {"Th0", ""}, {"CM", ""}};
}


Foam::meltdem::evaporationTerm::evaporationTerm(const fvMesh& mesh, const dictionary& properties)
:
    physicsTerm(mesh),
    model_(mesh, meltdemProperties::modelDict(properties, "evaporation"))
{}


bool Foam::meltdem::evaporationTerm::linearisedHeatLoss
(
    const volScalarField& T,
    const volScalarField& alpha1,
    volScalarField& q0,
    volScalarField& dqdT
) const
{
    q0 = model_.heatLoss(T, alpha1);
    dqdT = model_.heatLossDerivative(T, alpha1);
    return true;
}


Foam::tmp<Foam::volScalarField> Foam::meltdem::evaporationTerm::metalLossRate
(
    const volScalarField& T,
    const volScalarField& alpha1
) const
{
    if (!model_.massLoss())
    {
        return tmp<volScalarField>();
    }
    return model_.metalLossRate(T, alpha1);
}


Foam::tmp<Foam::volScalarField::Internal> Foam::meltdem::evaporationTerm::vapourVolumeRate
(
    const volScalarField& metalLossRate,
    const volScalarField& alpha1,
    const scalar rhoMetal,
    const scalar rhoGas
) const
{
    if (!model_.vapourJet())
    {
        return tmp<volScalarField::Internal>();
    }
    return model_.vapourVolumeRate(metalLossRate, alpha1, rhoMetal, rhoGas);
}
