/*---------------------------------------------------------------------------*\
    MeltDEM: surface forces of the metal-gas interface for meltdemFoam.
\*---------------------------------------------------------------------------*/

#include "surfaceForces.H"
#include "fvcGrad.H"
#include "fvcSnGrad.H"
#include "surfaceInterpolate.H"

#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const Foam::dimensionSet Foam::meltdem::surfaceForces::dimSigma
(
    1, 0, -2, 0, 0, 0, 0
);


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::meltdem::surfaceForces::surfaceForces
(
    const fvMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    sigma0_("sigma0", dimSigma, dict.get<scalar>("sigma0")),
    dSigmadT_
    (
        "dSigmadT",
        dimSigma/dimTemperature,
        dict.get<scalar>("dSigmadT")
    ),
    Tsigma0_("Tsigma0", dimTemperature, dict.get<scalar>("Tsigma0")),
    sigmaMin_("sigmaMin", dimSigma, dict.get<scalar>("sigmaMin")),
    deltaN_("deltaN", 1e-8/cbrt(average(mesh.V())))
{
    if (sigma0_.value() <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'sigma0' = " << sigma0_.value()
            << " must be > 0 [N/m]" << exit(FatalIOError);
    }
    if (Tsigma0_.value() <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'Tsigma0' = " << Tsigma0_.value()
            << " must be an absolute temperature > 0 [K]"
            << exit(FatalIOError);
    }
    if (sigmaMin_.value() < 0)
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'sigmaMin' = " << sigmaMin_.value()
            << " must be >= 0 [N/m]" << exit(FatalIOError);
    }
    if (sigmaMin_.value() > sigma0_.value())
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'sigmaMin' = " << sigmaMin_.value()
            << " exceeds 'sigma0' = " << sigma0_.value()
            << ": the bound would clip sigma at its own reference temperature"
            << exit(FatalIOError);
    }
    if (!std::isfinite(dSigmadT_.value()))
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'dSigmadT' = " << dSigmadT_.value()
            << " is not finite" << exit(FatalIOError);
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::meltdem::surfaceForces::sigma(const scalar T) const
{
    return max
    (
        sigma0_.value() + dSigmadT_.value()*(T - Tsigma0_.value()),
        sigmaMin_.value()
    );
}


Foam::tmp<Foam::volScalarField>
Foam::meltdem::surfaceForces::sigma(const volScalarField& T) const
{
    tmp<volScalarField> tsigma
    (
        max(sigma0_ + dSigmadT_*(T - Tsigma0_), sigmaMin_)
    );
    tsigma.ref().rename("sigma");
    return tsigma;
}


Foam::tmp<Foam::surfaceScalarField>
Foam::meltdem::surfaceForces::surfaceForce
(
    const volScalarField& alpha,
    const volScalarField& K,
    const volScalarField& T,
    const volScalarField* pRecoil
) const
{
    // Same discretisation as interfaceProperties::surfaceTensionForce(), so
    // that a uniform T reproduces interFoam's balanced force exactly
    if (pRecoil)
    {
        return
            fvc::interpolate(sigma(T)*K + *pRecoil)*fvc::snGrad(alpha);
    }

    return fvc::interpolate(sigma(T)*K)*fvc::snGrad(alpha);
}


Foam::tmp<Foam::volVectorField>
Foam::meltdem::surfaceForces::marangoniForce
(
    const volScalarField& alpha,
    const volScalarField& T
) const
{
    const volVectorField gradAlpha(fvc::grad(alpha, "nHat"));
    const volScalarField magGradAlpha(mag(gradAlpha));
    const volVectorField nHat(gradAlpha/(magGradAlpha + deltaN_));
    const volVectorField gradSigma(fvc::grad(sigma(T)));

    tmp<volVectorField> tforce
    (
        (gradSigma - nHat*(nHat & gradSigma))*magGradAlpha
    );
    tforce.ref().rename("marangoniForce");
    return tforce;
}


// ************************************************************************* //
