/*---------------------------------------------------------------------------*\
    MeltDEM

Application
    meltdemTermCheck

Description
    Evaluates one physics term of meltdemFoam (selected by name, as the solver
    selects it) on the start-time fields of a case, without solving: every
    hook the term acts through is called once and its result written as a
    field of the start time, for the term's test to compare with the closed
    form of its doc:

      termHeatSource       heatSource(alpha)                   [W/m3]
      termQ0, termDqdT     linearisedHeatLoss(T, alpha)        [W/m3], [W/m3/K]
      termSurfacePressure  surfacePressure(T)                  [Pa]
      termSurfaceForce     surfaceForce(...) reconstructed to the cells [N/m3]
      termMomentum         the force density of addMomentum: -(M & U) of a
                           matrix M holding the term alone     [N/m3]
      magGradAlpha         |grad alpha| as the models take it  [1/m]

    and prints "maxDeltaT <seconds>" where the term limits the step
    (maxDeltaT(alpha, T, rhoMean), rhoMean the mixture's mean density, or
    rho1/2 without transportProperties).

    Fields read: alpha.metal, T, and where present liquidFraction (else 1:
    all liquid), U; gravity
    from constant/g (zero without it); the metal and gas densities from -rho1
    and -rho2.
    surfaceForce needs constant/transportProperties (the two-phase mixture).
    Prints "hook <name> yes|no" for each hook.

Usage
    meltdemTermCheck -term NAME [-rho1 value] [-rho2 value]

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "physicsTerm.H"
#include "laserTerm.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "fvcReconstruct.H"

using namespace Foam;

namespace
{

tmp<volScalarField> readOrUniform
(
    const word& name,
    const fvMesh& mesh,
    const dimensionedScalar& value
)
{
    IOobject io(name, mesh.time().timeName(), mesh, IOobject::READ_IF_PRESENT);
    return tmp<volScalarField>::New(io, mesh, value);
}

void say(const word& hook, const bool acts)
{
    Info<< "hook " << hook << ' ' << (acts ? "yes" : "no") << nl;
}

}


int main(int argc, char *argv[])
{
    argList::addNote("Evaluate one physics term of meltdemFoam on a case's fields");
    argList::noParallel();
    argList::addOption("term", "name", "the physics term (meltdemFoam -listTerms)");
    argList::addOption("rho1", "value", "metal density [kg/m3] (default 1)");
    argList::addOption("rho2", "value", "gas density [kg/m3] (default 0)");

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"

    if (!args.found("term"))
    {
        FatalErrorInFunction << "-term NAME is required" << exit(FatalError);
    }
    const word termName(args.get<word>("term"));

    IOdictionary properties
    (
        IOobject
        (
            "meltdemProperties", runTime.constant(), mesh,
            IOobject::MUST_READ, IOobject::NO_WRITE
        )
    );

    volScalarField T
    (
        IOobject("T", runTime.timeName(), mesh, IOobject::MUST_READ),
        mesh
    );
    const volScalarField liquidFraction
    (
        readOrUniform("liquidFraction", mesh, dimensionedScalar("one", dimless, 1.0))
    );
    volVectorField U
    (
        IOobject("U", runTime.timeName(), mesh, IOobject::READ_IF_PRESENT),
        mesh,
        dimensionedVector("U", dimVelocity, Zero)
    );
    const surfaceScalarField phi("phi", fvc::flux(U));

    // the two-phase mixture (surfaceForce needs it) reads alpha.metal itself,
    // as in the solver; without transportProperties the field is read here
    autoPtr<immiscibleIncompressibleTwoPhaseMixture> mixture;
    autoPtr<volScalarField> alphaRead;
    if (isFile(runTime.constant()/"transportProperties"))
    {
        mixture.reset(new immiscibleIncompressibleTwoPhaseMixture(U, phi));
    }
    else
    {
        alphaRead.reset
        (
            new volScalarField
            (
                IOobject("alpha.metal", runTime.timeName(), mesh, IOobject::MUST_READ),
                mesh
            )
        );
    }
    const volScalarField& alpha1 = mixture ? mixture->alpha1() : alphaRead();
    const uniformDimensionedVectorField g
    (
        IOobject("g", runTime.constant(), mesh, IOobject::READ_IF_PRESENT),
        dimensionedVector("g", dimAcceleration, Zero)
    );
    const dimensionedScalar rho1
    (
        "rho1", dimDensity, args.getOrDefault<scalar>("rho1", 1)
    );
    const dimensionedScalar rho2
    (
        "rho2", dimDensity, args.getOrDefault<scalar>("rho2", 0)
    );

    autoPtr<meltdem::physicsTerm> term
    (
        meltdem::physicsTerm::New(termName, mesh, properties)
    );

    volScalarField magGradAlpha("magGradAlpha", mag(fvc::grad(alpha1)));
    magGradAlpha.write();

    // the laser sets its step's absorptivity first, as the solver does
    if (auto* laser = dynamic_cast<meltdem::laserTerm*>(term.get()))
    {
        laser->model().updateAbsorptivity(alpha1, T);
    }
    tmp<volScalarField> q(term->heatSource(alpha1));
    say("heatSource", q.valid());
    if (q.valid())
    {
        volScalarField out("termHeatSource", q());
        out.write();
    }

    volScalarField q0
    (
        IOobject("termQ0", runTime.timeName(), mesh),
        mesh,
        dimensionedScalar("zero", dimPower/dimVolume, Zero)
    );
    volScalarField dqdT
    (
        IOobject("termDqdT", runTime.timeName(), mesh),
        mesh,
        dimensionedScalar("zero", dimPower/dimVolume/dimTemperature, Zero)
    );
    const bool loses = term->linearisedHeatLoss(T, alpha1, q0, dqdT);
    say("linearisedHeatLoss", loses);
    if (loses)
    {
        q0.rename("termQ0");
        dqdT.rename("termDqdT");
        q0.write();
        dqdT.write();
    }

    tmp<volScalarField> p(term->surfacePressure(T));
    say("surfacePressure", p.valid());
    if (p.valid())
    {
        volScalarField out("termSurfacePressure", p());
        out.write();
    }

    if (mixture)
    {
        tmp<surfaceScalarField> f(term->surfaceForce(alpha1, mixture(), T, liquidFraction, nullptr));
        say("surfaceForce", f.valid());
        if (f.valid())
        {
            volVectorField out("termSurfaceForce", fvc::reconstruct(f()*mesh.magSf()));
            out.write();
        }
    }

    const scalar rhoMean =
        mixture
      ? 0.5*(mixture->rho1().value() + mixture->rho2().value())
      : 0.5*rho1.value();
    const scalar dtLimit = term->maxDeltaT(alpha1, T, rhoMean);
    say("maxDeltaT", dtLimit < GREAT);
    if (dtLimit < GREAT)
    {
        Info<< "maxDeltaT " << dtLimit << nl;
    }

    fvVectorMatrix M(U, dimForce);
    term->addMomentum(M, {alpha1, T, liquidFraction, rho1, rho2, g});
    const bool pushes = M.hasDiag() || M.hasUpper() || M.hasLower() || gMax(mag(M.source())) > 0;
    say("addMomentum", pushes);
    if (pushes)
    {
        volVectorField out("termMomentum", -(M & U));
        out.write();
    }

    Info<< "End" << nl;
    return 0;
}
