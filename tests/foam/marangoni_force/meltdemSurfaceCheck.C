/*---------------------------------------------------------------------------*\
    MeltDEM

Application
    meltdemSurfaceCheck

Description
    Evaluates Foam::meltdem::surfaceForces on a case without solving
    anything: sigma(T) at given temperatures, and the Marangoni force of the
    fields alpha and T of the start time (its volume integral, direction,
    and the share of it that is normal to the interface, which must vanish).
    The surfaceTension sub-dictionary is read from constant/meltdemProperties
    (or -dict).  Output lines are "key value..." for scripts.

Usage
    meltdemSurfaceCheck [-dict file] [-alpha alpha.metal] [-T "(300 1700)"]
        [-write]

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "surfaceForces.H"
#include "fvcReconstruct.H"

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Evaluate sigma(T) and the Marangoni force of meltdem::surfaceForces"
    );
    argList::noParallel();
    argList::addOption("dict", "file", "meltdemProperties file");
    argList::addOption("alpha", "name", "metal fraction field (alpha.metal)");
    argList::addOption("T", "list", "temperatures to print sigma at");
    argList::addOption
    (
        "recoil",
        "pressure",
        "uniform recoil pressure [Pa]: print the integral of its face force"
    );
    argList::addBoolOption("write", "write the marangoniForce field");

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"

    const fileName dictPath
    (
        args.opt<fileName>
        (
            "dict",
            runTime.constant()/"meltdemProperties"
        )
    );
    IOdictionary props
    (
        IOobject
        (
            dictPath.isAbsolute()
          ? dictPath
          : fileName(runTime.path()/dictPath),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );

    meltdem::surfaceForces forces(mesh, props.subDict("surfaceTension"));

    if (args.found("T"))
    {
        const scalarList Ts(args.getList<scalar>("T"));
        for (const scalar T : Ts)
        {
            Info<< "sigma " << T << ' ' << forces.sigma(T) << nl;
        }
    }

    const word alphaName(args.opt<word>("alpha", "alpha.metal"));
    volScalarField alpha
    (
        IOobject(alphaName, runTime.timeName(), mesh, IOobject::MUST_READ),
        mesh
    );
    volScalarField T
    (
        IOobject("T", runTime.timeName(), mesh, IOobject::MUST_READ),
        mesh
    );

    // all liquid: the forces at full strength
    const volScalarField liquid
    (
        IOobject("liquid", runTime.timeName(), mesh),
        mesh,
        dimensionedScalar("one", dimless, 1.0)
    );

    // one density: the density scaling is 1
    const dimensionedScalar rho("rho", dimDensity, 1);
    volVectorField F(forces.marangoniForce(alpha, T, liquid, rho, rho));

    // Interface normal as the force uses it, to measure what is not tangential
    const volVectorField gradAlpha(fvc::grad(alpha, "nHat"));
    const volScalarField magGradAlpha(mag(gradAlpha));

    vector total(Zero);
    scalar sumMag = 0, sumNormal = 0, maxMag = 0;
    forAll(F, celli)
    {
        const vector& f = F[celli];
        const scalar V = mesh.V()[celli];
        total += f*V;
        sumMag += mag(f)*V;
        maxMag = max(maxMag, mag(f));
        if (magGradAlpha[celli] > SMALL)
        {
            const vector n(gradAlpha[celli]/magGradAlpha[celli]);
            sumNormal += mag(n & f)*V;
        }
    }

    if (!std::isfinite(sumMag))
    {
        FatalErrorInFunction
            << "Marangoni force is not finite" << exit(FatalError);
    }

    Info<< "marangoniIntegral " << total.x() << ' ' << total.y() << ' '
        << total.z() << nl
        << "marangoniDirection "
        << (mag(total) > VSMALL ? total/mag(total) : vector::zero) << nl
        << "marangoniMagnitudeIntegral " << sumMag << nl
        << "marangoniNormalFraction "
        << (sumMag > VSMALL ? sumNormal/sumMag : 0) << nl
        << "marangoniMax " << maxMag << nl;

    // Interface-weighted mean curvature (nSmooth of the dictionary) and the
    // net CSF force, which must vanish for a closed interface
    const volScalarField K(forces.curvature(alpha));
    const scalarField w(magGradAlpha.primitiveField()*mesh.V());
    const volVectorField fCSF
    (
        fvc::reconstruct
        (
            forces.surfaceForce(alpha, K, T, liquid)*mesh.magSf()
        )
    );
    const vector netCSF(gSum(fCSF.primitiveField()*mesh.V()));
    Info<< "curvatureMean " << gSum(K.primitiveField()*w)/max(gSum(w), VSMALL)
        << nl
        << "csfNet " << netCSF.x() << ' ' << netCSF.y() << ' ' << netCSF.z()
        << nl
        << "csfMagnitudeIntegral " << gSum(mag(fCSF.primitiveField())*mesh.V())
        << nl;

    if (args.found("recoil"))
    {
        // Recoil alone (difference with and without it): must push into
        // the metal
        const volScalarField pRecoil
        (
            IOobject("pRecoil", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar
            (
                "pRecoil",
                dimPressure,
                args.get<scalar>("recoil")
            )
        );
        const volScalarField K0
        (
            IOobject("K0", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar("K0", dimless/dimLength, Zero)
        );
        const volVectorField fR
        (
            fvc::reconstruct
            (
                forces.surfaceForce(alpha, K0, T, liquid, &pRecoil)*mesh.magSf()
              - forces.surfaceForce(alpha, K0, T, liquid)*mesh.magSf()
            )
        );
        const vector netR(gSum(fR.primitiveField()*mesh.V()));
        Info<< "recoilIntegral " << netR.x() << ' ' << netR.y() << ' '
            << netR.z() << nl;
    }

    if (args.found("write"))
    {
        F.write();
        K.write();
    }

    Info<< "End" << nl;
    return 0;
}
