#include "physicsTerms.H"

#include "fvMatrices.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "laserTerm.H"
#include "meltdemProperties.H"

Foam::meltdem::physicsTerms::physicsTerms
(
    const fvMesh& mesh,
    const meltdemProperties& properties
)
:
    laser_(nullptr)
{
    const wordList& on = properties.terms();
    terms_.setSize(on.size());
    forAll(on, i)
    {
        terms_.set(i, physicsTerm::New(on[i], mesh, properties));
        if (laserTerm* l = dynamic_cast<laserTerm*>(&terms_[i]))
        {
            laser_ = &l->model();
        }
    }
}


bool Foam::meltdem::physicsTerms::heatSource
(
    const volScalarField& alpha1,
    volScalarField& source
) const
{
    bool any = false;
    for (const physicsTerm& t : terms_)
    {
        tmp<volScalarField> q(t.heatSource(alpha1));
        if (!q.valid()) continue;
        if (any) source += q;
        else source = q;
        any = true;
    }
    return any;
}


bool Foam::meltdem::physicsTerms::linearisedHeatLoss
(
    const volScalarField& T,
    const volScalarField& alpha1,
    volScalarField& q0,
    volScalarField& dqdT
) const
{
    bool any = false;
    for (const physicsTerm& t : terms_)
    {
        if (!any)
        {
            any = t.linearisedHeatLoss(T, alpha1, q0, dqdT);
            continue;
        }
        volScalarField q("q", q0), d("dqdT", dqdT);
        if (t.linearisedHeatLoss(T, alpha1, q, d))
        {
            q0 += q;
            dqdT += d;
        }
    }
    return any;
}


bool Foam::meltdem::physicsTerms::metalLossRate
(
    const volScalarField& T,
    const volScalarField& alpha1,
    volScalarField& rate
) const
{
    bool any = false;
    for (const physicsTerm& t : terms_)
    {
        tmp<volScalarField> r = t.metalLossRate(T, alpha1);
        if (!r.valid())
        {
            continue;
        }
        if (any)
        {
            rate.primitiveFieldRef() += r().primitiveField();
        }
        else
        {
            rate.primitiveFieldRef() = r().primitiveField();
        }
        any = true;
    }
    return any;
}


bool Foam::meltdem::physicsTerms::vapourVolumeRate
(
    const volScalarField& metalLossRate,
    const volScalarField& alpha1,
    const scalar rhoMetal,
    const scalar rhoGas,
    volScalarField::Internal& rate
) const
{
    bool any = false;
    for (const physicsTerm& t : terms_)
    {
        tmp<volScalarField::Internal> r = t.vapourVolumeRate(metalLossRate, alpha1, rhoMetal, rhoGas);
        if (!r.valid())
        {
            continue;
        }
        if (any)
        {
            rate.field() += r().field();
        }
        else
        {
            rate.field() = r().field();
        }
        any = true;
    }
    return any;
}


Foam::tmp<Foam::surfaceScalarField> Foam::meltdem::physicsTerms::surfaceForce
(
    const volScalarField& alpha1,
    const immiscibleIncompressibleTwoPhaseMixture& mixture,
    const volScalarField& T,
    const volScalarField& liquidFraction
) const
{
    tmp<volScalarField> pressure;
    for (const physicsTerm& t : terms_)
    {
        tmp<volScalarField> p(t.surfacePressure(T));
        if (!p.valid()) continue;
        if (pressure.valid()) pressure.ref() += p;
        else pressure = p;
    }
    for (const physicsTerm& t : terms_)
    {
        tmp<surfaceScalarField> f
        (
            t.surfaceForce
            (
                alpha1, mixture, T, liquidFraction,
                pressure.valid() ? &pressure() : nullptr
            )
        );
        if (f.valid()) return f;
    }
    return mixture.surfaceTensionForce();
}


Foam::scalar Foam::meltdem::physicsTerms::maxDeltaT
(
    const volScalarField& alpha1,
    const volScalarField& T,
    const scalar rhoMean
) const
{
    scalar dt = GREAT;
    for (const physicsTerm& t : terms_)
    {
        dt = min(dt, t.maxDeltaT(alpha1, T, rhoMean));
    }
    return dt;
}


bool Foam::meltdem::physicsTerms::needsMixtureCurvature
(
    const immiscibleIncompressibleTwoPhaseMixture& mixture
) const
{
    for (const physicsTerm& t : terms_)
    {
        if (t.usesMixtureCurvature()) return true;
    }
    // "sigma 0;" only: a model dictionary or a non-zero sigma keeps the curvature
    const entry* e = mixture.findEntry("sigma", keyType::LITERAL);
    if (!e || e->isDict()) return true;
    ITstream& is = e->stream();
    return !(is.size() == 1 && is[0].isNumber() && is[0].number() == 0);
}


void Foam::meltdem::physicsTerms::addMomentum
(
    fvVectorMatrix& UEqn,
    const physicsTerm::solverFields& fields
) const
{
    for (const physicsTerm& t : terms_)
    {
        t.addMomentum(UEqn, fields);
    }
}
