#include "particleCoupling.H"
#include "meltdemProperties.H"

#include "Time.H"

#include <chrono>
#include <cmath>
#include <string>
#include <unordered_map>

namespace mc = ::meltdem::coupling;

namespace
{

double seconds()
{
    using clock = std::chrono::steady_clock;
    return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

Foam::word requiredWord(const Foam::dictionary& d, const Foam::word& key)
{
    if (!d.found(key))
    {
        FatalIOErrorInFunction(d)
            << "missing entry '" << key << "' in " << d.name() << Foam::exit(Foam::FatalIOError);
    }
    return d.get<Foam::word>(key);
}

//- Where the particles of the records are, for the exchange
std::vector<::meltdem::coupling::ParticleShape> shapesOf
(
    const std::vector<::meltdem::coupling::ExchangeRecord>& records
)
{
    std::vector<::meltdem::coupling::ParticleShape> shapes;
    shapes.reserve(records.size());
    for (const auto& r : records) shapes.push_back({r.x, r.radius, r.id});
    return shapes;
}

} // End anonymous namespace


Foam::meltdem::particleCoupling::particleCoupling
(
    const fvMesh& mesh,
    const dictionary& meltdemDict,
    const scalar rhoMetal
)
:
    mesh_(mesh),
    dict_(meltdemDict.optionalSubDict("particles")),
    model_(mc::DistributionModel::Neighbours),
    fixedSubSteps_(0),
    warnedFixedStep_(false),
    thermal_(meltdemDict.subDict("physics").getOrDefault<bool>("energy", false)),
    oneWay_(!meltdemDict.subDict("physics").getOrDefault<bool>("flow", true)),
    distMesh_(mesh),
    haveLocated_(false),
    startHaveLocated_(false),
    subSteps_(0),
    exchangeSeconds_(0),
    lammpsSeconds_(0)
{
    if (!meltdemDict.found("particles") || !meltdemDict.isDict("particles"))
    {
        FatalIOErrorInFunction(meltdemDict)
            << "physics { particles on; } needs the sub-dictionary 'particles'"
            << " (lammpsInput, distribution)" << exit(FatalIOError);
    }
    meltdemProperties::checkEntries
    (
        dict_,
        {"lammpsInput", "distribution", "demStepsPerFluidStep", "lammpsLog", "laserShadow", "heatExchange"}
    );
    try
    {
        model_ = mc::parse_distribution_model(requiredWord(dict_, "distribution"));
    }
    catch (const std::invalid_argument& e)
    {
        FatalIOErrorInFunction(dict_)
            << "distribution: " << e.what() << exit(FatalIOError);
    }
    if (dict_.found("demStepsPerFluidStep"))
    {
        const ITstream& is = dict_.lookup("demStepsPerFluidStep");
        if (!(is[0].isWord() && is[0].wordToken() == "auto"))
        {
            fixedSubSteps_ = dict_.get<label>("demStepsPerFluidStep");
            if (fixedSubSteps_ < 1)
            {
                FatalIOErrorInFunction(dict_)
                    << "demStepsPerFluidStep must be auto or >= 1, not "
                    << fixedSubSteps_ << exit(FatalIOError);
            }
        }
    }
    // off: the beam passes the particles (LMD, Codina2019 4.1: the powder's own absorption
    // is negligible beside the pool's, and the ray grid is costly over a wide beam)
    const bool laserShadow = dict_.getOrDefault<bool>("laserShadow", true);
    const word heatExchange(dict_.getOrDefault<word>("heatExchange", "twoBody"));
    if (heatExchange != "twoBody" && heatExchange != "implicit")
    {
        FatalIOErrorInFunction(dict_)
            << "heatExchange must be twoBody or implicit, not " << heatExchange << exit(FatalIOError);
    }
    if (oneWay_ && heatExchange == "implicit")
    {
        FatalIOErrorInFunction(dict_)
            << "heatExchange implicit exchanges the particles' heat in the energy solve, which"
            << " one-way coupling (physics flow off) does not feed back: use twoBody"
            << exit(FatalIOError);
    }
    Info<< "Particles: distribution " << mc::to_string(model_) << ", heat exchange "
        << heatExchange << (oneWay_ ? ", one-way (the continuum is given, flow off)" : "")
        << ", cell search (master rank) " << distMesh_.searchName() << endl;

    comm_.reset(new particleCommunicator);
    const MPI_Comm comm = comm_->comm();
    checkpoint_.reset(new particleCheckpoint(mesh.time(), comm));

    // a run started at a write time with a complete checkpoint resumes from it
    double lammpsTime = 0;
    std::string ledgerState;
    const bool resumed = checkpoint_->read(lammpsTime, ledgerState);
    const fileName restartFile
    (
        resumed
      ? checkpoint_->dir(mesh.time().timeName())/::meltdem::LammpsCouplingHost::kRestartFile
      : fileName()
    );
    if (resumed)
    {
        Info<< "Particles: resuming from the checkpoint " << restartFile
            << " (LAMMPS time " << lammpsTime << " s)" << endl;
    }
    host_.reset
    (
        new particleHost(mesh, meltdemDict, dict_, comm, distMesh_, thermal_, restartFile, lammpsTime)
    );
    ::meltdem::LammpsCouplingHost& lammps = (*host_)();
    lossWatch_.reset(new insertionLossWatch(lammps, comm));

    exchange_.reset(new mc::ParallelExchange(distMesh_, model_, comm));
    startExchange_.reset(new mc::ParallelExchange(distMesh_, model_, comm));
    sampling_.reset(new particleSampling(mesh, comm, thermal_, laserShadow));
    sampling_->setGiven(oneWay_);
    bounds_.reset(new temperatureBounds(mesh, comm));
    deposition_.reset(new particleDeposition(mesh, rhoMetal, model_));
    if (heatExchange == "implicit" && thermal_)
    {
        heat_.reset(new particleHeatExchange(mesh, lammps.material().Tmelt));
        sampling_->setImplicitHeat(true);
    }
    ledger_.reset
    (
        new particleLedgerOutput
        (
            mesh, comm, lammps, resumed ? &ledgerState : nullptr,
            checkpoint_->dir(mesh.time().timeName()), oneWay_
        )
    );
    ranks_.reset(new rankLoadOutput(mesh, comm, resumed));

    Info<< "Particles: " << lammps.particles() << " particles, DEM step "
        << lammps.timestep() << " s, coupling interval "
        << (fixedSubSteps_ ? name(fixedSubSteps_) + " DEM steps" : word("auto"))
        << nl << endl;
}


Foam::meltdem::particleCoupling::~particleCoupling()
{
    // LAMMPS and the exchanges before the communicator they use
    ledger_.reset();
    ranks_.reset();
    host_.reset();
    exchange_.reset();
    startExchange_.reset();
    comm_.reset();
}


void Foam::meltdem::particleCoupling::subCycles
(
    const Time& runTime,
    label& n,
    scalar& dtSub
) const
{
    // a sub-cycle longer than maxSubSteps is an input mistake: a DEM step of the wrong
    // unit or order of magnitude
    const scalar maxSubSteps = 1e8;
    const scalar dtDem = (*host_)().timestep();
    const scalar remaining = runTime.endTime().value() - runTime.value();
    const scalar dtFluid =
        remaining > 0 ? min(runTime.deltaTValue(), remaining) : runTime.deltaTValue();
    n = fixedSubSteps_;
    dtSub = dtDem;
    if (!n)
    {
        // as many DEM steps as the fluid step needs, each shortened to fill it exactly
        // (never longer than the DEM's own step): the fluid step is what its Courant
        // limit allows, not rounded down to whole DEM steps (which, below 5 DEM steps,
        // could never grow by the solver's factor 1.2)
        const scalar steps = std::ceil(dtFluid/dtDem*(1 - 1e-12));
        if (!(steps <= maxSubSteps))
        {
            FatalErrorInFunction
                << "one fluid step of " << dtFluid << " s would take " << steps << " DEM steps of "
                << dtDem << " s (more than " << maxSubSteps << "): check the LAMMPS input's "
                << "timestep (or fix powder/dt) against maxDeltaT in system/controlDict"
                << exit(FatalError);
        }
        n = max(label(1), label(steps));
        dtSub = dtFluid/n;
    }
    else
    {
        n = min(n, max(label(1), label(std::ceil(remaining/dtDem - 1e-9))));
    }
}


void Foam::meltdem::particleCoupling::fixedStepOverrun
(
    const Time& runTime,
    const bool adjustTimeStep,
    const scalar step
)
{
    // the step adjustTimeStep chose (maxCo, maxAlphaCo, maxDeltaT, the capillary limit) is
    // runTime's until the sub-cycle sets it; only a fixed sub-cycle can run past it. The
    // first step's is controlDict's deltaT, not a limit
    const bool adjustable = adjustTimeStep && runTime.timeIndex() != runTime.startTimeIndex();
    const scalar allowed = runTime.deltaTValue();
    const scalar overrun = fixedSubSteps_ && adjustable && allowed > 0 ? step/allowed : 0;
    bounds_->setFixedStepOverrun(overrun, fixedSubSteps_, step);
    if (overrun > 1 + 1e-9 && !warnedFixedStep_)
    {
        WarningInFunction
            << "demStepsPerFluidStep " << fixedSubSteps_ << " fixes the fluid step at " << step
            << " s, " << overrun << " times the step maxCo, maxAlphaCo and maxDeltaT allow at t = "
            << runTime.value() << " s: the flow runs past its Courant limit (a stop naming the "
            << "temperature range says so again). Use demStepsPerFluidStep auto, or a smaller "
            << "N. (Warned once per run.)" << endl;
        warnedFixedStep_ = true;
    }
}


void Foam::meltdem::particleCoupling::advance
(
    Time& runTime,
    const bool adjustTimeStep,
    const fluidFields& f
)
{
    ::meltdem::LammpsCouplingHost& lammps = (*host_)();
    const MPI_Comm comm = comm_->comm();
    // the clocks start together on every rank: a rank's wait for the others' fluid solve
    // or DEM steps is not booked as exchange time
    MPI_Barrier(comm);
    double t0 = seconds();

    // 1. the fluid each particle sees, fixed over the step
    std::vector<mc::ExchangeRecord>& start = start_;
    lammps.local_particles(start);
    relocate(shapesOf(start));
    metalCells_ = 0;
    for (const scalar a : f.alphaMetal.primitiveField()) metalCells_ += a >= 0.5;
    const scalarField cp(f.rhoCp.primitiveField()/f.rho.primitiveField());
    const mc::CellFluidFields cells(particleSampling::cellFields(f, cp));
    std::vector<mc::SampledFluid>& sampled = sampled_;
    sampling_->sample(*exchange_, cells, f, start, *bounds_, sampled);
    std::vector<mc::SolidSurface> solid;
    if (lammps.solid_metal_wall())
    {
        sampling_->solidSurfaces(*exchange_, f, start, runTime.deltaTValue(), solid);
    }

    // 2. whole DEM steps up to the fluid step, the light fixed at mid-step
    const scalar dtDem = lammps.timestep();
    label n;
    scalar dtSub;
    subCycles(runTime, n, dtSub);
    fixedStepOverrun(runTime, adjustTimeStep, n*dtSub);
    std::vector<double> light;
    sampling_->shade(runTime, start, n*dtSub, light);
    bounds_->setHeated(sampling_->heated());
    std::vector<std::int64_t> ids;
    std::vector<mc::FluidState> states;
    sampling_->fluidStates(*exchange_, start, sampled, solid, light, ids, states);
    lammps.set_fluid(ids, states, exchange_->rank());

    const std::int64_t before = lammps.particles();
    const double tLmp0 = lammps.time();
    exchangeSeconds_ += seconds() - t0;
    const double w0 = seconds();
    std::vector<mc::ExchangeRecord>& records = records_;
    const bool shortened = dtSub < dtDem*(1 - 1e-12);
    if (shortened) lammps.set_timestep(dtSub);
    // the sub-cycle spans n*dtSub exactly, whatever fix powder/dt does to the DEM step meanwhile
    const label steps = lammps.advance(int(n), records, n*dtSub);
    bounds_->widen(records);
    // back to the DEM's own step unless the input changed it meanwhile (fix powder/dt)
    if (shortened && lammps.timestep() == dtSub) lammps.set_timestep(dtDem);
    MPI_Barrier(comm);
    lammpsSeconds_ += seconds() - w0;
    t0 = seconds();
    subSteps_ = steps;
    const scalar elapsed = lammps.time() - tLmp0;
    runTime.setDeltaT(elapsed, false);

    // particles lost by LAMMPS itself cannot be booked: refuse to go on
    std::int64_t nRecords = std::int64_t(records.size());
    MPI_Allreduce(MPI_IN_PLACE, &nRecords, 1, MPI_INT64_T, MPI_SUM, comm);
    if (nRecords < before)
    {
        FatalErrorInFunction
            << "LAMMPS lost " << before - nRecords << " particle(s) during the step "
            << "(they left its box); make the LAMMPS box larger than the mesh so that "
            << "particles leave the mesh first and are booked as outflow"
            << exit(FatalError);
    }

    // a particle that melted away within the step (mass 0): its melt is spread with the
    // size it had at the start of the step, not its last solid size (one cell in fine
    // meshes); and it stopped absorbing its light: the beam the shadow held back for the
    // rest of the step heats its melt (the continuum gets it with the melt's enthalpy), so
    // continuum + particles still absorb eta P
    auto atStart = start.cbegin();  // both by ascending id
    for (auto& r : records)
    {
        if (r.mass > 0) continue;
        while (atStart != start.cend() && atStart->id < r.id) ++atStart;
        if (atStart != start.cend() && atStart->id == r.id) r.radius = max(r.radius, atStart->radius);
        if (!(r.light > 0)) continue;
        const double rest = r.light*elapsed - r.external_heat;
        if (rest > 0)
        {
            r.external_heat += rest;
            r.enthalpy_out += rest;
        }
    }

    // 3./4. where each particle is now: inside -> deposit, outside -> outflow;
    // the start-of-step location kept for what the particles took
    std::swap(exchange_, startExchange_);
    std::swap(located_, startLocated_);
    std::swap(haveLocated_, startHaveLocated_);
    relocate(shapesOf(records));
    if (heat_)
    {
        // the energy solve exchanges the heat: none is taken from the cells here
        for (auto& r : records) r.heat_absorbed = 0;
        heat_->prepare(records, *exchange_, f.T, elapsed);
    }
    std::vector<std::int64_t> leaving;
    deposition_->deposit(records, *exchange_, *startExchange_, cells, elapsed, inside_, lost_, leaving);
    if (oneWay_) deposition_->clear();

    std::int64_t nLeaving = std::int64_t(leaving.size());
    MPI_Allreduce(MPI_IN_PLACE, &nLeaving, 1, MPI_INT64_T, MPI_SUM, comm);
    if (nLeaving)
    {
        lammps.remove(leaving);
        Info<< "Particles: " << nLeaving << " left the mesh (booked as outflow)" << endl;
    }
    exchangeSeconds_ += seconds() - t0;

    Info<< "Particles: " << lammps.particles() << " in " << n << " DEM steps of "
        << dtSub << " s; handed over "
        << gSum(deposition_->massSource().field()*mesh_.V())*elapsed << " kg of metal"
        << (oneWay_ ? " (one-way: none fed back)" : "") << endl;
}


void Foam::meltdem::particleCoupling::book(const functionObjects::meltdemBalance& balance)
{
    ::meltdem::LammpsCouplingHost& lammps = (*host_)();
    if (heat_) heat_->settle(*exchange_, inside_, lammps);
    ledger_->book(balance.lastStep(), inside_, lost_, lammps, subSteps_, exchangeSeconds_, lammpsSeconds_);
    std::int64_t present = 0;
    for (const auto& r : records_) present += r.mass > 0;
    ranks_->write(metalCells_, present, {exchange_.get(), startExchange_.get()});
    lossWatch_->check(lost_, lammps, distMesh_.globalBounds());
    bounds_->check(deposition_->enthalpySource());
}


void Foam::meltdem::particleCoupling::meshChanged()
{
    distMesh_.update();
    haveLocated_ = false;
    startHaveLocated_ = false;
}


void Foam::meltdem::particleCoupling::globalParticles
(
    List<point>& centres,
    scalarList& radii
)
{
    if (!haveLocated_)
    {
        // nothing located since the run began (a resumed run's first step):
        // the particles where LAMMPS has them now, as an uninterrupted run has them
        std::vector<mc::ExchangeRecord> now;
        (*host_)().local_particles(now);
        relocate(shapesOf(now));
    }
    // every rank's particles (the refinement criteria look for grains near any cell)
    const MPI_Comm comm = comm_->comm();
    int size = 1;
    MPI_Comm_size(comm, &size);
    std::vector<double> mine;
    mine.reserve(4*located_.size());
    for (const mc::ParticleShape& p : located_)
    {
        mine.insert(mine.end(), {p.x.x(), p.x.y(), p.x.z(), p.radius});
    }
    const int count = int(mine.size());
    std::vector<int> counts(size), offsets(size, 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> all(std::size_t(offsets[size - 1] + counts[size - 1]));
    MPI_Allgatherv
    (
        mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm
    );
    centres.setSize(label(all.size()/4));
    radii.setSize(label(all.size()/4));
    forAll(centres, i)
    {
        centres[i] = point(all[4*i], all[4*i + 1], all[4*i + 2]);
        radii[i] = all[4*i + 3];
    }
}


void Foam::meltdem::particleCoupling::relocate(const std::vector<mc::ParticleShape>& shapes)
{
    // the particles at the start of a step are those at the end of the last one unless
    // some left, melted away or came: then the weights are still valid
    // (a collective decision: every rank locates, or none)
    int same = haveLocated_ && shapes.size() == located_.size() ? 1 : 0;
    for (std::size_t i = 0; same && i < shapes.size(); ++i)
    {
        same = shapes[i].id == located_[i].id && shapes[i].radius == located_[i].radius
            && shapes[i].x == located_[i].x;
    }
    MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm_->comm());
    if (same) return;
    exchange_->locate(shapes);
    located_ = shapes;
    haveLocated_ = true;
}
