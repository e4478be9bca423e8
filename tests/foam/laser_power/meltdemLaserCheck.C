/*---------------------------------------------------------------------------*\
    MeltDEM

Application
    meltdemLaserCheck

Description
    Evaluates Foam::meltdem::laserHeatSource on the alpha.metal field of the
    start time at the given times (beam on/off, position, hit fraction and the
    volume integral of the source, recomputed here with gSum), and
    Foam::meltdem::evaporationModel at given temperatures. Sub-dictionaries
    laser / evaporation of constant/meltdemProperties. Runs in parallel.
    Output lines are "key value..." for scripts.

Usage
    meltdemLaserCheck [-times "(0 1e-4)"] [-T "(3000 2500)"] [-write]

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "laserHeatSource.H"
#include "evaporationModel.H"

int main(int argc, char *argv[])
{
    argList::addNote("Evaluate meltdem::laserHeatSource and evaporationModel");
    argList::addOption("times", "list", "times to evaluate the laser at");
    argList::addOption("T", "list", "temperatures to evaluate evaporation at");
    argList::addOption("alpha", "name", "metal fraction field (alpha.metal)");
    argList::addBoolOption("write", "write the laser field of each time");
    argList::addOption("dt", "value", "time step ending at each time (default 1e-6)");

    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"

    IOdictionary props
    (
        IOobject("meltdemProperties", runTime.constant(), mesh,
                 IOobject::MUST_READ, IOobject::NO_WRITE, false)
    );

    if (args.found("T"))
    {
        meltdem::evaporationModel evap(mesh, props.subDict("evaporation"));
        for (const scalar T : args.getList<scalar>("T"))
        {
            Info<< "evaporation T " << T << " pv " << evap.pv(T)
                << " flux " << evap.fluxLoss(T)
                << " dfluxdT " << evap.fluxLossDerivative(T) << nl;
        }
        // the field path: uniform T, interface integral of heatLoss
        volScalarField alpha
        (
            IOobject(args.opt<word>("alpha", "alpha.metal"), runTime.timeName(),
                     mesh, IOobject::MUST_READ),
            mesh
        );
        const scalar T0 = args.getList<scalar>("T").first();
        volScalarField T
        (
            IOobject("T", runTime.timeName(), mesh),
            mesh,
            dimensionedScalar("T", dimTemperature, T0)
        );
        const volScalarField q(evap.heatLoss(T, alpha));
        const volScalarField p(evap.recoilPressure(T));
        Info<< "evaporationField T " << T0 << " heatLossIntegral "
            << gSum(q.primitiveField()*mesh.V()) << " gasCellLoss "
            << gSum(pos0(0.5 - alpha.primitiveField())*q.primitiveField()*mesh.V())
            << " pRecoilMax " << gMax(p) << nl;
    }

    if (args.found("times"))
    {
        volScalarField alpha
        (
            IOobject(args.opt<word>("alpha", "alpha.metal"), runTime.timeName(),
                     mesh, IOobject::MUST_READ),
            mesh
        );
        meltdem::laserHeatSource laser(mesh, props.subDict("laser"));
        label index = runTime.timeIndex();
        for (const scalar t : args.getList<scalar>("times"))
        {
            runTime.setTime(t, ++index);
            // the step (t - dt, t] (the laser averages its power over it)
            runTime.setDeltaT(args.opt<scalar>("dt", 1e-6), false);
            const volScalarField q(laser.heatSource(alpha));
            const vector x0 = laser.position();
            Info<< "laser t " << t << " on " << laser.on() << " onFraction "
                << laser.onFraction()
                << " position " << x0.x() << ' ' << x0.y() << ' ' << x0.z()
                << " absorbed " << laser.absorbedPower()
                << " hitFraction " << laser.hitFraction()
                << " integral " << gSum(q.primitiveField()*mesh.V())
                << " min " << gMin(q.primitiveField()) << nl;
            if (args.found("write"))
            {
                volScalarField out("laserHeatSource", q);
                out.write();
            }
        }
    }

    Info<< "End" << endl;
    return 0;
}
