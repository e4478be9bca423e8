/*---------------------------------------------------------------------------*\
    MeltDEM: evaporation recoil pressure and heat loss (see evaporationModel.H).
\*---------------------------------------------------------------------------*/

#include "evaporationModel.H"
#include "meltdemProperties.H"
#include "fvc.H"
#include "fvm.H"
#include "fvMatrices.H"
#include "zeroGradientFvPatchFields.H"

const Foam::scalar Foam::meltdem::evaporationModel::recoilFactor = 0.54;
const Foam::scalar Foam::meltdem::evaporationModel::massFlowFactor = 0.82;
const Foam::scalar Foam::meltdem::evaporationModel::gasAlpha = 0.01;

namespace
{
Foam::scalar readChecked
(
    const Foam::dictionary& dict,
    const Foam::word& key,
    const bool strictlyPositive
)
{
    using namespace Foam;
    const scalar v = dict.get<scalar>(key);
    if (strictlyPositive ? !(v > 0) : !(v >= 0))
    {
        FatalIOErrorInFunction(dict)
            << key << " (" << v << ") must be " << (strictlyPositive ? "> 0" : ">= 0")
            << " in " << dict.name() << exit(FatalIOError);
    }
    return v;
}
}

Foam::meltdem::evaporationModel::evaporationModel
(
    const fvMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    pAmbient_(readChecked(dict, "pAmbient", true)),
    CT_(readChecked(dict, "CT", true)),
    Tboil_(readChecked(dict, "Tboil", true)),
    hv_(readChecked(dict, "hv", false)),
    cp_(readChecked(dict, "cp", false)),
    Th0_(readChecked(dict, "Th0", false)),
    CM_(readChecked(dict, "CM", true)),
    cs_(dict.getOrDefault<scalar>("stickingCoefficient", 1)),
    massLoss_(dict.getOrDefault<bool>("massLoss", false)),
    vapourJet_(dict.getOrDefault<bool>("vapourJet", false)),
    spreadLength_(dict.getOrDefault<scalar>("vapourSpread", 0))
{
    meltdemProperties::checkEntries
    (
        dict,
        {
            "pAmbient", "CT", "Tboil", "hv", "cp", "Th0", "CM", "stickingCoefficient", "massLoss",
            "vapourJet", "vapourSpread"
        }
    );
    if (spreadLength_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "vapourSpread (" << spreadLength_ << ") must be >= 0 in " << dict.name()
            << exit(FatalIOError);
    }
    if (vapourJet_ && !massLoss_)
    {
        FatalIOErrorInFunction(dict)
            << "vapourJet on needs massLoss on (the vapour's volume is the evaporated metal's) in "
            << dict.name() << exit(FatalIOError);
    }
    if (cs_ < 0 || cs_ > 1)
    {
        FatalIOErrorInFunction(dict)
            << "stickingCoefficient (" << cs_ << ") must be in [0,1] in "
            << dict.name() << exit(FatalIOError);
    }
    Info<< "evaporationModel: C_P = " << recoilFactor*pAmbient_ << " Pa, C_T = "
        << CT_ << " K, T_v = " << Tboil_ << " K" << endl;
    if (massLoss_)
    {
        Info<< "evaporationModel: massLoss on: the evaporated metal leaves with its own"
            << " enthalpy; heat loss mdot h_v (cp, Th0 not used)" << endl;
    }
}


Foam::scalar Foam::meltdem::evaporationModel::pv(const scalar T) const
{
    // T <= 0 cannot occur physically; guard the 1/T (p_v -> 0 there)
    const scalar Tpos = max(T, SMALL);
    return recoilFactor*pAmbient_*exp(-CT_*(1/Tpos - 1/Tboil_));
}


Foam::scalar Foam::meltdem::evaporationModel::massFlux(const scalar T) const
{
    const scalar Tpos = max(T, SMALL);
    return massFlowFactor*cs_*pv(Tpos)*sqrt(CM_/Tpos);
}


Foam::scalar Foam::meltdem::evaporationModel::fluxLoss(const scalar T) const
{
    const scalar Tpos = max(T, SMALL);
    const scalar mdot = massFlux(Tpos);
    if (massLoss_)
    {
        return mdot*hv_;
    }
    // below T_h0 h(T) < 0; the loss stays >= 0 (hv dominates in practice)
    return max(mdot*(hv_ + cp_*(Tpos - Th0_)), scalar(0));
}


Foam::scalar Foam::meltdem::evaporationModel::fluxLossDerivative
(
    const scalar T
) const
{
    const scalar Tpos = max(T, SMALL);
    const scalar mdot = massFlux(Tpos);
    const scalar h = massLoss_ ? hv_ : hv_ + cp_*(Tpos - Th0_);
    const scalar dhdT = massLoss_ ? 0 : cp_;
    if (mdot*h <= 0)
    {
        return 0;
    }
    // d mdot/dT = mdot (C_T/T^2 - 1/(2T))
    return max(mdot*(CT_/sqr(Tpos) - 0.5/Tpos)*h + mdot*dhdT, scalar(0));
}


Foam::tmp<Foam::volScalarField>
Foam::meltdem::evaporationModel::heatLossDerivative
(
    const volScalarField& T,
    const volScalarField& alphaMetal
) const
{
    tmp<volScalarField> tq
    (
        new volScalarField
        (
            IOobject("evaporationHeatLossDerivative", T.time().timeName(), mesh_,
                     IOobject::NO_READ, IOobject::NO_WRITE, false),
            mag(fvc::grad(alphaMetal))
        )
    );
    volScalarField& q = tq.ref();
    q.dimensions().reset(dimPower/dimVolume/dimTemperature);
    forAll(q, celli)
    {
        const scalar w = 2*max(min(alphaMetal[celli], scalar(1)), scalar(0));
        q[celli] *= w*fluxLossDerivative(T[celli]);
    }
    q.boundaryFieldRef() = Zero;
    return tq;
}


Foam::tmp<Foam::volScalarField>
Foam::meltdem::evaporationModel::recoilPressure(const volScalarField& T) const
{
    tmp<volScalarField> tp
    (
        new volScalarField
        (
            IOobject("pRecoil", T.time().timeName(), mesh_,
                     IOobject::NO_READ, IOobject::NO_WRITE, false),
            mesh_,
            dimensionedScalar("zero", dimPressure, 0)
        )
    );
    volScalarField& p = tp.ref();
    forAll(p, celli)
    {
        p[celli] = pv(T[celli]);
    }
    volScalarField::Boundary& pb = p.boundaryFieldRef();
    forAll(pb, patchi)
    {
        forAll(pb[patchi], facei)
        {
            pb[patchi][facei] = pv(T.boundaryField()[patchi][facei]);
        }
    }
    return tp;
}


Foam::tmp<Foam::volScalarField> Foam::meltdem::evaporationModel::metalLossRate
(
    const volScalarField& T,
    const volScalarField& alphaMetal
) const
{
    tmp<volScalarField> tm
    (
        new volScalarField
        (
            IOobject("evaporationMetalLossRate", T.time().timeName(), mesh_,
                     IOobject::NO_READ, IOobject::NO_WRITE, false),
            mag(fvc::grad(alphaMetal))
        )
    );
    volScalarField& m = tm.ref();
    m.dimensions().reset(dimDensity/dimTime);
    forAll(m, celli)
    {
        const scalar w = 2*max(min(alphaMetal[celli], scalar(1)), scalar(0));
        m[celli] *= massLoss_ ? w*massFlux(T[celli]) : 0;
    }
    m.boundaryFieldRef() = Zero;
    return tm;
}


Foam::tmp<Foam::volScalarField::Internal>
Foam::meltdem::evaporationModel::vapourVolumeRate
(
    const volScalarField& metalLossRate,
    const volScalarField& alphaMetal,
    const scalar rhoMetal,
    const scalar rhoGas
) const
{
    tmp<volScalarField::Internal> tv
    (
        new volScalarField::Internal
        (
            IOobject("evaporationVapourVolumeRate", mesh_.time().timeName(), mesh_,
                     IOobject::NO_READ, IOobject::NO_WRITE, false),
            mesh_,
            dimensionedScalar("zero", inv(dimTime), 0)
        )
    );
    if (!vapourJet_)
    {
        return tv;
    }
    // the evaporated metal's volume as gas, where the metal loses it
    const scalar expansion = 1/rhoGas - 1/rhoMetal;
    volScalarField spread
    (
        IOobject("vapourSpread", mesh_.time().timeName(), mesh_, IOobject::NO_READ, IOobject::NO_WRITE, false),
        mesh_,
        dimensionedScalar("zero", inv(dimTime), 0),
        zeroGradientFvPatchScalarField::typeName
    );
    spread.primitiveFieldRef() = expansion*metalLossRate.primitiveField();
    // (the laplacian's non-orthogonal correction on a refined mesh takes the gradient of
    // this start value: its processor patches must hold the neighbours' cells, as in serial)
    spread.correctBoundaryConditions();
    const scalarField& V = mesh_.V().field();
    const scalar total = gSum(spread.primitiveField()*V);
    if (total <= 0)
    {
        return tv;
    }
    // spread over a length of two cells (a conservative implicit smoothing) and kept in
    // the gas cells beyond the interface, normalised to the same total (HardtWondra2008):
    // the interface itself is carried by a divergence-free flow
    const scalar length = spreadLength_ > 0 ? spreadLength_ : 2/gMax(mesh_.deltaCoeffs().primitiveField());
    const volScalarField::Internal source("vapourSource", spread());
    fvScalarMatrix smoothing
    (
        fvm::Sp(dimensionedScalar("one", dimless, 1), spread)
      - fvm::laplacian(dimensionedScalar("L2", dimArea, sqr(length)), spread)
     ==
        source
    );
    dictionary solverControls;
    solverControls.add("solver", "PCG");
    solverControls.add("preconditioner", "DIC");
    solverControls.add("tolerance", 1e-12);
    solverControls.add("relTol", 0);
    smoothing.solve(solverControls);
    scalarField& v = tv.ref().field();
    forAll(v, celli)
    {
        v[celli] = alphaMetal[celli] < gasAlpha ? max(spread[celli], scalar(0)) : 0;
    }
    const scalar kept = gSum(v*V);
    if (kept > 0)
    {
        v *= total/kept;
    }
    else
    {
        // no gas cell within reach of the smoothing: where the metal loses it
        v = expansion*metalLossRate.primitiveField();
    }
    return tv;
}


Foam::tmp<Foam::volScalarField> Foam::meltdem::evaporationModel::heatLoss
(
    const volScalarField& T,
    const volScalarField& alphaMetal
) const
{
    tmp<volScalarField> tq
    (
        new volScalarField
        (
            IOobject("evaporationHeatLossModel", T.time().timeName(), mesh_,
                     IOobject::NO_READ, IOobject::NO_WRITE, false),
            mag(fvc::grad(alphaMetal))
        )
    );
    volScalarField& q = tq.ref();
    q.dimensions().reset(dimPower/dimVolume);
    forAll(q, celli)
    {
        const scalar w = 2*max(min(alphaMetal[celli], scalar(1)), scalar(0));
        q[celli] *= w*fluxLoss(T[celli]);
    }
    volScalarField::Boundary& qb = q.boundaryFieldRef();
    forAll(qb, patchi)
    {
        forAll(qb[patchi], facei)
        {
            const scalar w =
                2*max(min(alphaMetal.boundaryField()[patchi][facei], scalar(1)), scalar(0));
            qb[patchi][facei] *= w*fluxLoss(T.boundaryField()[patchi][facei]);
        }
    }
    return tq;
}

// ************************************************************************* //
