#include "surfaceTensionTerm.H"

#include "fvcDiv.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "meltdemProperties.H"

namespace Foam
{
namespace meltdem
{
    addMeltdemPhysicsTerm(surfaceTensionTerm);
}
}


Foam::meltdem::physicsTerm::termInfo Foam::meltdem::surfaceTensionTerm::info()
{
    return {"surfaceTension", 20, {"flow"},
            {{"surfaceTension", {{"sigma0", ""}, {"dSigmadT", ""}, {"Tsigma0", ""}, {"sigmaMin", ""}}}},
            "sigma(T) CSF surface tension", {"momentum"}};
}


Foam::meltdem::surfaceTensionTerm::surfaceTensionTerm
(
    const fvMesh& mesh,
    const dictionary& properties
)
:
    physicsTerm(mesh),
    forces_(mesh, meltdemProperties::modelDict(properties, "surfaceTension"))
{}


Foam::tmp<Foam::surfaceScalarField> Foam::meltdem::surfaceTensionTerm::surfaceForce
(
    const volScalarField& alpha1,
    const immiscibleIncompressibleTwoPhaseMixture& mixture,
    const volScalarField& T,
    const volScalarField& liquidFraction,
    const volScalarField* pressure
) const
{
    return forces_.surfaceForce
    (
        alpha1, volScalarField("K", -fvc::div(mixture.nHatf())), T,
        liquidFraction, pressure
    );
}


Foam::scalar Foam::meltdem::surfaceTensionTerm::maxDeltaT
(
    const volScalarField& alpha1,
    const volScalarField& T,
    const scalar rhoMean
) const
{
    return forces_.capillaryDeltaT(alpha1, T, rhoMean);
}
