/*---------------------------------------------------------------------------*\
    MeltDEM: surface forces of the metal-gas interface for meltdemFoam.
\*---------------------------------------------------------------------------*/

#include "surfaceForces.H"
#include "meltdemProperties.H"
#include "fvcGrad.H"
#include "fvcSnGrad.H"
#include "surfaceInterpolate.H"
#include "fvcDiv.H"
#include "fvcAverage.H"
#include "mathematicalConstants.H"

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
    deltaN_("deltaN", 1e-8/cbrt(average(mesh.V()))),
    nSmooth_(dict.getOrDefault<label>("nSmooth", 0)),
    marangoniDensityScaled_(dict.getOrDefault<bool>("marangoniDensityScaled", false))
{
    meltdemProperties::checkEntries
    (
        dict, {"sigma0", "dSigmadT", "Tsigma0", "sigmaMin", "nSmooth", "marangoniDensityScaled"}
    );
    if (nSmooth_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "surfaceTension entry 'nSmooth' = " << nSmooth_
            << " must be >= 0" << exit(FatalIOError);
    }
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


Foam::tmp<Foam::volScalarField>
Foam::meltdem::surfaceForces::curvature(const volScalarField& alpha) const
{
    volScalarField alphaS("alphaSmooth", 1.0*alpha);
    for (label i = 0; i < nSmooth_; ++i)
    {
        alphaS = fvc::average(fvc::interpolate(alphaS));
    }

    // interfaceProperties::calculateK() on the smoothed field
    const surfaceVectorField gradAlphaf
    (
        fvc::interpolate(fvc::grad(alphaS, "nHat"))
    );
    const surfaceScalarField nHatf
    (
        (gradAlphaf/(mag(gradAlphaf) + deltaN_)) & mesh_.Sf()
    );

    tmp<volScalarField> tK(-fvc::div(nHatf));
    tK.ref().rename("K");
    return tK;
}


Foam::tmp<Foam::surfaceScalarField>
Foam::meltdem::surfaceForces::surfaceForce
(
    const volScalarField& alpha,
    const volScalarField& K,
    const volScalarField& T,
    const volScalarField& liquidFraction,
    const volScalarField* pRecoil
) const
{
    // Same discretisation as interfaceProperties::surfaceTensionForce(), so
    // that a uniform T (and nSmooth 0) reproduces interFoam's balanced force
    tmp<volScalarField> tKs;
    if (nSmooth_ > 0)
    {
        tKs = curvature(alpha);
    }
    const volScalarField& Kused = nSmooth_ > 0 ? tKs() : K;

    if (pRecoil)
    {
        return
            fvc::interpolate(liquidFraction*sigma(T)*Kused + *pRecoil)
           *fvc::snGrad(alpha);
    }

    return fvc::interpolate(liquidFraction*sigma(T)*Kused)*fvc::snGrad(alpha);
}


Foam::tmp<Foam::volVectorField>
Foam::meltdem::surfaceForces::marangoniForce
(
    const volScalarField& alpha,
    const volScalarField& T,
    const volScalarField& liquidFraction,
    const dimensionedScalar& rho1,
    const dimensionedScalar& rho2
) const
{
    const volVectorField gradAlpha(fvc::grad(alpha, "nHat"));
    const volScalarField magGradAlpha(mag(gradAlpha));
    const volVectorField nHat(gradAlpha/(magGradAlpha + deltaN_));
    const volVectorField gradSigma(fvc::grad(sigma(T)));

    tmp<volVectorField> tforce
    (
        liquidFraction*(gradSigma - nHat*(nHat & gradSigma))*magGradAlpha
    );
    if (marangoniDensityScaled_)
    {
        const volScalarField alphaBounded(min(max(alpha, scalar(0)), scalar(1)));
        tforce.ref() *= 2*(alphaBounded*rho1 + (1 - alphaBounded)*rho2)/(rho1 + rho2);
    }
    tforce.ref().rename("marangoniForce");
    return tforce;
}



Foam::scalar Foam::meltdem::surfaceForces::capillaryDeltaT
(
    const volScalarField& alpha,
    const volScalarField& T,
    const scalar rhoMean
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const vectorField& C = mesh_.C();
    const auto crossed = [](const scalar a)
    {
        return a > 0.01 && a < 0.99;
    };
    scalar dt2 = GREAT;
    // the face of cells at distance h with temperatures Ta, Tb, where either is crossed
    const auto face = [&](const scalar h, const scalar Ta, const scalar Tb)
    {
        const scalar s = max(sigma(Ta), sigma(Tb));
        dt2 = min(dt2, rhoMean*h*h*h/(constant::mathematical::twoPi*s));
    };
    forAll(nei, facei)
    {
        const label a = own[facei], b = nei[facei];
        if (crossed(alpha[a]) || crossed(alpha[b]))
        {
            face(mag(C[b] - C[a]), T[a], T[b]);
        }
    }
    // processor (and cyclic) faces as the internal faces they are in serial: the
    // neighbours' cells from the coupled patches
    forAll(alpha.boundaryField(), patchi)
    {
        const fvPatchScalarField& alphap = alpha.boundaryField()[patchi];
        if (!alphap.coupled())
        {
            continue;
        }
        const scalarField alphaN(alphap.patchNeighbourField());
        const scalarField TN(T.boundaryField()[patchi].patchNeighbourField());
        const vectorField delta(alphap.patch().delta());
        const labelUList& cells = alphap.patch().faceCells();
        forAll(cells, i)
        {
            if (crossed(alpha[cells[i]]) || crossed(alphaN[i]))
            {
                face(mag(delta[i]), T[cells[i]], TN[i]);
            }
        }
    }
    reduce(dt2, minOp<scalar>());
    return dt2 < GREAT ? Foam::sqrt(dt2) : GREAT;
}

// ************************************************************************* //
