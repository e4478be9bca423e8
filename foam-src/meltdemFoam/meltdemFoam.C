/*---------------------------------------------------------------------------*\
    MeltDEM: meltdemFoam

Description
    Melt-pool solver: two incompressible immiscible phases, metal and gas, with
    interFoam's VOF (MULES, PIMPLE) so that metal mass is conserved to
    round-off, plus what a powder-AM melt pool needs, each term switched on in
    constant/meltdemProperties only when a scene needs it:
      - energy in enthalpy form, latent heat between solidus and liquidus,
        liquid fraction (Codina2019 eq. 2.5-2.7 mixture properties);
      - Darcy/Carman-Kozeny sink in solid and mushy metal (Codina2019 eq. 2.10);
      - CSF surface tension with sigma(T), Marangoni force, recoil pressure;
      - Gaussian laser deposited at the interface, evaporation heat loss;
      - Boussinesq buoyancy.
    With every term off it is interFoam (surface tension then comes from
    transportProperties' sigma, as there).

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "exactRestartTime.H"
#include "dynamicFvMesh.H"
#include "CMULES.H"
#include "EulerDdtScheme.H"
#include "localEulerDdtScheme.H"
#include "CrankNicolsonDdtScheme.H"
#include "subCycle.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "CorrectPhi.H"
#include "fvcSmooth.H"

#include "meltdemProperties.H"
#include "physicsTerms.H"
#include "meltdemBalance.H"
#include "particleCoupling.H"
#include "caseCheckpoint.H"
#include "caseLock.H"
#include "meshRefinement.H"
#include "interfaceDeltaN.H"
#include "correctMixture.H"
#include "dynamicRefineFvMesh.H"
#include "energyTransport.H"
#include "upwind.H"
#include "gaussConvectionScheme.H"

#include <malloc.h>

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    // memory freed at the end of a step stays with the process for the next one: glibc would
    // hand large blocks (fields, the exchange's per-particle arrays) back and fault them in
    // again every step (bench/scaling.md)
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);

    // the physics switches and the entries they read, for `meltdem check`
    for (int i = 1; i < argc; ++i)
    {
        if (std::string(argv[i]) == "-listTerms")
        {
            Foam::meltdem::physicsTerm::writeTable(std::cout);
            return 0;
        }
    }

    argList::addNote
    (
        "Melt-pool solver for powder additive manufacturing: VOF metal/gas,"
        " melting and solidification, surface forces, laser, evaporation."
        " -listTerms prints the physics switches and their entries (JSON)."
    );

    #include "postProcess.H"

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    #include "createExactRestartTime.H"

    // one run per case folder, before anything is read or written
    Foam::meltdem::caseLock lock(runTime);
    // refinement{} in meltdemProperties: the mesh type and its entries, before the mesh
    const bool refining = Foam::meltdem::meshRefinement::writeMeshDict(runTime);
    #include "createDynamicFvMesh.H"
    #include "initContinuityErrs.H"
    #include "createDyMControls.H"
    #include "createFields.H"
    #include "createMeltdemFields.H"
    #include "checkStartFields.H"
    #include "createMeshRefinement.H"
    #include "createAlphaFluxes.H"
    #include "initCorrectPhi.H"
    #include "createUfIfPresent.H"

    turbulence->validate();

    if (!LTS)
    {
        #include "CourantNo.H"
        #include "setInitialDeltaT.H"
    }

    // a fixed step over the capillary limit is said once (capillaryDeltaT.H)
    bool capillaryLimitExceeded = false;

    Foam::meltdem::caseCheckpoint checkpoint(runTime);

    Info<< "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        // the last write time is a checkpoint once its function objects ran (run())
        checkpoint.markComplete();

        #include "readDyMControls.H"

        if (LTS)
        {
            #include "setRDeltaT.H"
        }
        else
        {
            #include "CourantNo.H"
            #include "alphaCourantNo.H"
            #include "setDeltaT.H"
            #include "capillaryDeltaT.H"
        }

        #include "refineMesh.H"

        if (terms.laser())
        {
            // eta(T) of this step, for the grains and the continuum alike
            terms.laser()->updateAbsorptivity(alpha1, T);
        }

        if (particles.valid())
        {
            // LAMMPS advances first and fixes the step to the time it advanced
            const volScalarField muMixture("muMixture", mixture.mu());
            particles->advance
            (
                runTime,
                adjustTimeStep,
                {T, kappa, rho, muMixture, rhoCp, U, alpha1, liquidFraction}
            );
        }

        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl << endl;

        if (!physics.flow)
        {
            // conduction only: the phases stay where they are (but evaporate)
            #include "removeEvaporatedMetal.H"
            #include "TEqn.H"
        }

        while (physics.flow && pimple.loop())
        {
            if (pimple.firstIter() || moveMeshOuterCorrectors)
            {
                // (a refining mesh updated before the step, refineMesh.H)
                if (!refinement.valid())
                {
                    mesh.update();
                }

                if (mesh.changing())
                {
                    if (mesh.topoChanging())
                    {
                        talphaPhi1Corr0.clear();
                    }

                    gh = (g & mesh.C()) - ghRef;
                    ghf = (g & mesh.Cf()) - ghRef;

                    MRF.update();

                    if (correctPhi)
                    {
                        phi = mesh.Sf() & Uf();

                        #include "correctPhi.H"

                        fvc::makeRelative(phi, U);

                        Foam::meltdem::correctMixture(mixture, mixtureCurvature);
                    }

                    if (checkMeshCourantNo)
                    {
                        #include "meshCourantNo.H"
                    }
                }
            }

            #include "alphaControls.H"
            #include "alphaEqnSubCycle.H"

            if (particles.valid())
            {
                // the metal melted this step (explicit: exactly what was handed over)
                particles->addMetal(alpha1, alpha2);
                rho == alpha1*rho1 + alpha2*rho2;
            }

            #include "removeEvaporatedMetal.H"

            Foam::meltdem::correctMixture(mixture, mixtureCurvature);

            // energy with the same metal fluxes that moved alpha
            #include "TEqn.H"

            if (pimple.frozenFlow())
            {
                continue;
            }

            #include "UEqn.H"

            while (pimple.correct())
            {
                #include "pEqn.H"
            }

            if (pimple.turbCorr())
            {
                turbulence->correct();
            }
        }

        #include "physicsForce.H"

        const bool writeOk = runTime.write();
        if (refinement.valid() && runTime.writeTime())
        {
            Foam::meltdem::writeInterfaceDeltaN(runTime, mixture);
        }

        if (particles.valid())
        {
            particleBalance->execute();
            particles->book(particleBalance());
            if (runTime.writeTime())
            {
                particles->write();
            }
        }
        checkpoint.written(writeOk);

        runTime.printExecutionTime(Info);
    }
    checkpoint.markComplete();

    Info<< "End\n" << endl;

    return 0;
}
