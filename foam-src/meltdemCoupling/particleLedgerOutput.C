#include "particleLedgerOutput.H"

#include "OSspecific.H"
#include "Time.H"

#include <sstream>

namespace mc = ::meltdem::coupling;

Foam::meltdem::particleLedgerOutput::particleLedgerOutput
(
    const fvMesh& mesh,
    MPI_Comm comm,
    const ::meltdem::LammpsCouplingHost& lammps,
    const std::string* ledgerState,
    const fileName& checkpointDir,
    const bool oneWay
)
:
    mesh_(mesh),
    comm_(comm),
    ledger_(new mc::ConservationLedger(comm)),
    oneWay_(oneWay)
{
    // powder drawn before the coupling starts is already in the particles or pending
    mc::Amounts pendingNow;
    lammps.insertion_store(drawnBefore_, pendingNow);

    const fileName dir(mesh.time().globalPath()/"postProcessing"/"particleLedger");
    if (Pstream::master()) mkDir(dir);
    if (ledgerState)
    {
        // the ledger goes on from the checkpoint; the rows a run wrote past it before it
        // stopped are dropped
        try
        {
            std::istringstream is(*ledgerState);
            ledger_->load_state(is);
            ledger_->resume_csv(dir/"ledger.csv");
        }
        catch (const std::exception& e)
        {
            FatalErrorInFunction
                << "cannot resume the particle ledger from " << checkpointDir << ": " << e.what()
                << exit(FatalError);
        }
        resumeParticlesCsv(dir/"particles.csv", ledger_->last().step + 1);
    }
    else
    {
        ledger_->open_csv(dir/"ledger.csv");
        if (Pstream::master())
        {
            particlesCsv_.reset(new std::ofstream(dir/"particles.csv"));
            *particlesCsv_
                << "time,dt,dem_steps,particles,solid_mass,particle_enthalpy,heat_absorbed,"
                << "mass_melted,enthalpy_handed_over,momentum_handed_over_x,"
                << "momentum_handed_over_y,momentum_handed_over_z,drag_impulse_x,"
                << "drag_impulse_y,drag_impulse_z,laser_heat,exchange_seconds,lammps_seconds\n";
        }
    }
}


void Foam::meltdem::particleLedgerOutput::resumeParticlesCsv
(
    const fileName& file,
    std::int64_t nRows
)
{
    if (!Pstream::master()) return;
    std::vector<std::string> lines;
    {
        std::ifstream in(file);
        std::string line;
        while (std::getline(in, line) && std::int64_t(lines.size()) <= nRows)
        {
            lines.push_back(line);
        }
    }
    particlesCsv_.reset(new std::ofstream(file, std::ios::trunc));
    for (const auto& l : lines) *particlesCsv_ << l << '\n';
    particlesCsv_->flush();
}


void Foam::meltdem::particleLedgerOutput::book
(
    const functionObjects::meltdemBalance::stepBudget& b,
    const std::vector<mc::ExchangeRecord>& inside,
    const std::vector<mc::ExchangeRecord>& lost,
    const ::meltdem::LammpsCouplingHost& lammps,
    const label demSteps,
    const scalar exchangeSeconds,
    const scalar lammpsSeconds
)
{
    mc::ConservationLedger& L = *ledger_;
    L.begin_step(mesh_.time().value(), mesh_.time().deltaTValue());
    for (const auto& r : inside)
    {
        L.book_particle(r);
        if (oneWay_)
        {
            // the continuum is given: what the particle handed over leaves with the given
            // gas, what it took came from it
            const mc::Amounts ex = mc::net_to_continuum(r);
            for (int q = 0; q < mc::kComponents; ++q)
            {
                L.book(mc::kContinuumSource, mc::Component(q), -ex[q]);
            }
        }
    }
    for (const auto& r : lost)
    {
        // outside the mesh nothing was deposited: its melt leaves with it; the heat and impulse
        // it took during the step came from the cells it sampled at the start
        mc::ExchangeRecord kept(r);
        kept.mass_out = 0;
        kept.enthalpy_out = 0;
        kept.momentum_out = Eigen::Vector3d::Zero();
        L.book_lost(kept);
        L.book(mc::kLost, mc::make_amounts(r.mass_out, r.enthalpy_out, r.momentum_out));
    }
    // powder from fix powder/insert: what was drawn this step is fed into the pending
    // store, from which the inserted particles come (they then appear in the records)
    mc::Amounts drawn, pending;
    lammps.insertion_store(drawn, pending);
    if (Pstream::master())
    {
        for (int q = 0; q < mc::kComponents; ++q)
        {
            L.book(mc::kFeed, mc::Component(q), drawn[q] - drawnBefore_[q]);
        }
        L.book(mc::kPending, pending);
    }
    drawnBefore_ = drawn;
    if (Pstream::master())
    {
        L.book(mc::kContinuum, mc::make_amounts(b.M, b.H, Eigen::Vector3d(b.P.x(), b.P.y(), b.P.z())));
        const mc::Amounts through = mc::make_amounts
        (
            b.massIn, b.enthalpyIn,
            Eigen::Vector3d(b.momentumIn.x(), b.momentumIn.y(), b.momentumIn.z())
        );
        for (int q = 0; q < mc::kComponents; ++q)
        {
            if (through[q] >= 0)
            {
                L.book(mc::kBoundaryIn, mc::Component(q), through[q]);
            }
            else
            {
                L.book(mc::kBoundaryOut, mc::Component(q), -through[q]);
            }
        }
        L.book
        (
            mc::kContinuumSource,
            mc::make_amounts
            (
                -b.evaporatedMass, b.laserE - b.evapE - b.evaporatedEnthalpy,
                Eigen::Vector3d
                (
                    b.gravityImpulse.x() + b.physicsForceImpulse.x() - b.evaporatedMomentum.x(),
                    b.gravityImpulse.y() + b.physicsForceImpulse.y() - b.evaporatedMomentum.y(),
                    b.gravityImpulse.z() + b.physicsForceImpulse.z() - b.evaporatedMomentum.z()
                )
            )
        );
    }
    const mc::LedgerStep& s = L.end_step();

    // what the particles did this step (global sums), for plots and the heat split
    double sums[12] = {};  // the 12th: laser energy the particles absorbed
    for (const auto* list : {&inside, &lost})
    {
        for (const auto& r : *list)
        {
            sums[0] += r.mass;
            sums[1] += r.mass*r.h + r.heat_owed;
            sums[2] += r.heat_absorbed;
            sums[3] += r.mass_out;
            sums[4] += r.enthalpy_out;
            for (int d = 0; d < 3; ++d)
            {
                sums[5 + d] += r.momentum_out[d];
                sums[8 + d] += r.impulse_from_fluid[d];
            }
            sums[11] += r.external_heat;
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, sums, 12, MPI_DOUBLE, MPI_SUM, comm_);
    if (particlesCsv_)
    {
        std::ostream& o = *particlesCsv_;
        o.precision(17);
        o << mesh_.time().value() << ',' << mesh_.time().deltaTValue() << ',' << demSteps
          << ',' << s.particles;
        for (int k = 0; k < 12; ++k) o << ',' << sums[k];
        o << ',' << exchangeSeconds << ',' << lammpsSeconds << '\n';
        o.flush();
    }
    Info<< "Particle ledger: continuum relative errors mass "
        << s.continuum_error[mc::kMass] << " enthalpy " << s.continuum_error[mc::kEnthalpy]
        << " momentum (" << s.continuum_error[mc::kMomX] << " "
        << s.continuum_error[mc::kMomY] << " " << s.continuum_error[mc::kMomZ] << ")"
        << nl << endl;
}
