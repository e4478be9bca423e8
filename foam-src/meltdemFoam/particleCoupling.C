#include "particleCoupling.H"

#include "OSspecific.H"
#include "Time.H"
#include "uniformDimensionedFields.H"
#include "meltdem/coupling/particle_melting.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <cmath>
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

// Particles (buoyancy, eq. 2.14, and fix gravity) and the continuum (hydrostatics) must feel
// the same gravity: the impulse the particles take from the fluid is the fluid's to lose.
void checkGravity
(
    const Foam::fvMesh& mesh,
    const ::meltdem::LammpsCouplingHost& lammps,
    const Foam::dictionary& dict
)
{
    using namespace Foam;
    double gl[3];
    lammps.gravity(gl);
    const vector gLammps(gl[0], gl[1], gl[2]);
    // meltdemFoam registers g on Time (meshObjects::gravity)
    vector gFoam(Zero);
    if (mesh.time().foundObject<uniformDimensionedVectorField>("g"))
    {
        gFoam = mesh.time().lookupObject<uniformDimensionedVectorField>("g").value();
    }
    if (mag(gLammps - gFoam) > 1e-9*max(mag(gLammps), mag(gFoam)))
    {
        FatalIOErrorInFunction(dict)
            << "mismatched gravity: the fix gravity of " << dict.get<word>("lammpsInput")
            << " gives " << gLammps << " m/s2, constant/g is " << gFoam
            << ": particles and continuum must feel the same gravity" << exit(FatalIOError);
    }
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
    rhoMetal_(rhoMetal),
    largestCell_(Foam::cbrt(gMax(mesh.V().field()))),
    fixedSubSteps_(0),
    comm_(MPI_COMM_NULL),
    ownMpi_(false),
    distMesh_(mesh),
    model_(mc::DistributionModel::Neighbours),
    massSource_
    (
        IOobject("particleMassSource", mesh.time().timeName(), mesh),
        mesh, dimensionedScalar("zero", dimDensity/dimTime, 0)
    ),
    volumeSource_
    (
        IOobject("particleVolumeSource", mesh.time().timeName(), mesh),
        mesh, dimensionedScalar("zero", dimless/dimTime, 0)
    ),
    enthalpySource_
    (
        IOobject("particleEnthalpySource", mesh.time().timeName(), mesh),
        mesh, dimensionedScalar("zero", dimPower/dimVolume, 0)
    ),
    momentumSource_
    (
        IOobject("particleMomentumSource", mesh.time().timeName(), mesh),
        mesh, dimensionedVector("zero", dimForce/dimVolume, Zero)
    ),
    subSteps_(0),
    exchangeSeconds_(0),
    lammpsSeconds_(0),
    thermal_
    (
        meltdemDict.subDict("physics").getOrDefault<bool>("energy", false)
    ),
    Tlo_(0),
    Thi_(0),
    exchangeTime_(GREAT),
    boundsSet_(false),
    heated_(false),
    maxInitialId_(0),
    placedEarly_(0),
    lostEarly_(0),
    lostEarlyCount_(0),
    steps_(0),
    warnedLost_(false),
    laser_(nullptr),
    haveLocated_(false),
    startHaveLocated_(false)
{
    if (!meltdemDict.found("particles") || !meltdemDict.isDict("particles"))
    {
        FatalIOErrorInFunction(meltdemDict)
            << "physics { particles on; } needs the sub-dictionary 'particles'"
            << " (lammpsInput, distribution)" << exit(FatalIOError);
    }

    const word distribution(requiredWord(dict_, "distribution"));
    try
    {
        model_ = mc::parse_distribution_model(distribution);
    }
    catch (const std::invalid_argument& e)
    {
        FatalIOErrorInFunction(dict_)
            << "distribution: " << e.what() << exit(FatalIOError);
    }

    if (dict_.found("demStepsPerFluidStep"))
    {
        const ITstream& is = dict_.lookup("demStepsPerFluidStep");
        const token& t = is[0];
        if (t.isWord() && t.wordToken() == "auto")
        {
            fixedSubSteps_ = 0;
        }
        else
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

    // off: the beam passes the particles (LMD, thesis 4.1: the powder's own absorption is
    // negligible beside the pool's, and the ray grid is costly over a wide beam)
    laserShadow_ = dict_.getOrDefault<bool>("laserShadow", true);

    // the case folder (not processorN/): LAMMPS reads one input for all ranks
    const fileName input(mesh.time().globalPath()/requiredWord(dict_, "lammpsInput"));
    const fileName log
    (
        mesh.time().globalPath()/dict_.getOrDefault<word>("lammpsLog", "log.lammps")
    );
    Info<< "Particles: LAMMPS input " << input << ", log " << log
        << ", distribution " << mc::to_string(model_) << endl;
    // OpenFOAM initialises MPI only with -parallel; LAMMPS and the exchange need it
    // always. Both get their own communicator, apart from OpenFOAM's messages.
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
        MPI_Init(nullptr, nullptr);
        ownMpi_ = true;
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
    // a run started at a write time with a complete checkpoint resumes from it
    double lammpsTime = 0;
    std::string ledgerState;
    const bool resumed = readCheckpoint(lammpsTime, ledgerState);
    const fileName restartFile
    (
        resumed ? checkpointDir(mesh.time().timeName())/::meltdem::LammpsCouplingHost::kRestartFile : fileName()
    );
    if (resumed)
    {
        Info<< "Particles: resuming from the checkpoint " << restartFile
            << " (LAMMPS time " << lammpsTime << " s)" << endl;
    }
    try
    {
        lammps_.reset
        (
            new ::meltdem::LammpsCouplingHost
            (
                comm_, input, log, false, restartFile, lammpsTime
            )
        );
    }
    catch (const ::meltdem::LammpsSetupError& e)
    {
        FatalIOErrorInFunction(dict_)
            << "lammpsInput: " << e.what() << exit(FatalIOError);
    }

    if (!lammps_->resume_limitation().empty())
    {
        WarningInFunction
            << "this run can not be resumed from its checkpoints: "
            << lammps_->resume_limitation() << endl;
    }
    checkMaterial(meltdemDict);
    checkDomains();
    checkGravity(mesh, *lammps_, dict_);
    // powder drawn before the coupling starts is already in the particles or pending
    mc::Amounts pendingNow;
    lammps_->insertion_store(drawnBefore_, pendingNow);
    placedEarly_ = -(drawnBefore_[mc::kMass] - pendingNow[mc::kMass]);
    {
        std::vector<mc::ExchangeRecord> now;
        lammps_->local_particles(now);
        for (const auto& r : now) maxInitialId_ = std::max(maxInitialId_, r.id);
        MPI_Allreduce(MPI_IN_PLACE, &maxInitialId_, 1, MPI_INT64_T, MPI_MAX, comm_);
    }

    exchange_.reset(new mc::ParallelExchange(distMesh_, model_, comm_));
    startExchange_.reset(new mc::ParallelExchange(distMesh_, model_, comm_));
    ledger_.reset(new mc::ConservationLedger(comm_));
    const fileName dir(mesh.time().globalPath()/"postProcessing"/"particleLedger");
    if (Pstream::master()) mkDir(dir);
    if (resumed)
    {
        // the ledger goes on from the checkpoint; the rows a run wrote past it before it
        // stopped are dropped
        try
        {
            std::istringstream is(ledgerState);
            ledger_->load_state(is);
            ledger_->resume_csv(dir/"ledger.csv");
        }
        catch (const std::exception& e)
        {
            FatalErrorInFunction
                << "cannot resume the particle ledger from "
                << checkpointDir(mesh.time().timeName()) << ": " << e.what()
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

    Info<< "Particles: " << lammps_->particles() << " particles, DEM step "
        << lammps_->timestep() << " s, coupling interval "
        << (fixedSubSteps_ ? name(fixedSubSteps_) + " DEM steps" : word("auto"))
        << nl << endl;
}


Foam::meltdem::particleCoupling::~particleCoupling()
{
    lammps_.reset();
    exchange_.reset();
    startExchange_.reset();
    ledger_.reset();
    MPI_Comm_free(&comm_);
    if (ownMpi_) MPI_Finalize();
}


void Foam::meltdem::particleCoupling::checkMaterial(const dictionary& meltdemDict) const
{
    const mc::MeltMaterial& p = lammps_->material();
    if (!thermal_)
    {
        // without the energy equation the continuum has no T, k, cp for the particles'
        // heating (eq. 2.13) and no solid metal: the particles are isothermal and exchange
        // momentum only (binder jetting: a liquid binder, no phase change)
        if (lammps_->solid_metal_wall())
        {
            FatalIOErrorInFunction(meltdemDict.subDict("physics"))
                << "fix " << lammps_->melt_fix_id() << " powder/melt keyword solid_metal "
                << "needs 'energy on': without the energy equation there is no solid metal"
                << exit(FatalIOError);
        }
        Info<< "Particles: energy off, isothermal particles (drag and buoyancy only: "
            << "no heat exchange, no melting)" << endl;
        return;
    }
    const dictionary& md = meltdemDict.subDict("metal");
    const scalar cp = md.get<scalar>("cp"), L = md.get<scalar>("L");
    const scalar Ts = md.get<scalar>("Tsolidus"), Tl = md.get<scalar>("Tliquidus");
    // the particles hand over cp Tm + L per kilogram (eq. 2.9); the continuum must
    // read that as liquid metal at Tm, so both sides need the same material
    if (mag(p.cp - cp) > 1e-9*cp)
    {
        FatalIOErrorInFunction(md)
            << "cp " << cp << " differs from fix " << lammps_->melt_fix_id()
            << " powder/melt cp " << p.cp << ": particles and melt must be the same metal"
            << exit(FatalIOError);
    }
    if (mag(p.latent - L) > 1e-9*max(L, SMALL))
    {
        FatalIOErrorInFunction(md)
            << "L " << L << " differs from fix " << lammps_->melt_fix_id()
            << " powder/melt latent " << p.latent << exit(FatalIOError);
    }
    if (p.Tmelt < Ts - 1e-9 || p.Tmelt > Tl + 1e-9)
    {
        FatalIOErrorInFunction(md)
            << "fix " << lammps_->melt_fix_id() << " powder/melt Tmelt " << p.Tmelt
            << " is outside [Tsolidus, Tliquidus] = [" << Ts << ", " << Tl << "]"
            << exit(FatalIOError);
    }
}


void Foam::meltdem::particleCoupling::checkDomains() const
{
    const boundBox mb(distMesh_.globalBounds());
    double lo[3], hi[3];
    int periodic[3];
    lammps_->box(lo, hi, periodic);
    const scalar tol = 1e-9*mag(mb.span());
    const char* axis = "xyz";
    for (direction d = 0; d < 3; ++d)
    {
        const bool covers = lo[d] <= mb.min()[d] + tol && hi[d] >= mb.max()[d] - tol;
        const bool equal = mag(lo[d] - mb.min()[d]) <= tol && mag(hi[d] - mb.max()[d]) <= tol;
        if (!covers || (periodic[d] && !equal))
        {
            FatalIOErrorInFunction(dict_)
                << "mismatched domains: the LAMMPS box in " << axis[d] << " is ["
                << lo[d] << ", " << hi[d] << "], the mesh spans [" << mb.min()[d]
                << ", " << mb.max()[d] << "]. The box must contain the mesh (particles "
                << "leaving the mesh are booked as outflow before LAMMPS could lose "
                << "them) and equal it along periodic directions"
                << exit(FatalIOError);
        }
    }

    // every particle must start inside the mesh
    std::vector<mc::ExchangeRecord> now;
    lammps_->local_particles(now);
    mc::ParallelExchange probe(distMesh_, mc::DistributionModel::Centre, comm_);
    probe.locate(shapesOf(now));
    for (std::int64_t g = 0; g < probe.global_particles(); ++g)
    {
        if (!probe.global_inside(g))
        {
            FatalIOErrorInFunction(dict_)
                << "particle " << probe.global_id(g) << " of " << dict_.get<word>("lammpsInput")
                << " is outside the mesh at the start; move it inside or enlarge the mesh"
                << exit(FatalIOError);
        }
    }
}


void Foam::meltdem::particleCoupling::advance(Time& runTime, const fluidFields& f)
{
    double t0 = seconds();
    const label nCells = mesh_.nCells();

    // 1. the fluid each particle sees, fixed over the step
    std::vector<mc::ExchangeRecord> start;
    lammps_->local_particles(start);
    relocate(shapesOf(start));

    const scalarField cp(f.rhoCp.primitiveField()/f.rho.primitiveField());
    const mc::CellFluidFields cells
    {
        f.T.primitiveField().cdata(),
        f.kappa.primitiveField().cdata(),
        f.rho.primitiveField().cdata(),
        f.mu.primitiveField().cdata(),
        cp.cdata(),
        reinterpret_cast<const double*>(f.U.primitiveField().cdata()),
        f.alphaMetal.primitiveField().cdata(),
        f.liquidFraction.primitiveField().cdata(),
        mesh_.V().cdata()
    };
    std::vector<mc::SampledFluid> sampled;
    exchange_->sample_global(cells, sampled);
    if (thermal_)
    {
        // the range no exchange may leave, and the worst cell's C/G for the message
        const std::size_t offset = exchange_->local_offset();
        std::vector<mc::Amounts> g(start.size(), mc::Amounts{});
        scalar Tplo = GREAT, Tphi = -GREAT;
        for (std::size_t i = 0; i < start.size(); ++i)
        {
            if (!exchange_->inside(i)) continue;
            g[i][0] = mc::particle_conductance
            (
                sampled[offset + i].fluid, 2*start[i].radius, start[i].v.data()
            );
            Tplo = min(Tplo, start[i].T);
            Tphi = max(Tphi, start[i].T);
        }
        std::vector<mc::Amounts> gCells(std::size_t(nCells), mc::Amounts{});
        exchange_->deposit(g, gCells);
        const scalarField& V = mesh_.V();
        std::vector<double> heatCapacity(V.size()), conductance(V.size());
        forAll(V, celli)
        {
            heatCapacity[celli] = f.rhoCp[celli]*V[celli];
            conductance[celli] = gCells[celli][0];
        }
        exchangeTime_ = returnReduce
        (
            mc::heat_exchange_time(heatCapacity.data(), conductance.data(), V.size()),
            minOp<scalar>()
        );
        Tlo_ = min(returnReduce(Tplo, minOp<scalar>()), min(f.T).value());
        Thi_ = max(returnReduce(Tphi, maxOp<scalar>()), max(f.T).value());
        boundsSet_ = true;
    }
    // solid metal near each particle (cells whose metal is mostly solid): a wall for it
    std::vector<mc::SolidSurface> solid;
    if (lammps_->solid_metal_wall())
    {
        const scalarField solidFraction
        (
            f.alphaMetal.primitiveField()*(1 - f.liquidFraction.primitiveField())
        );
        // reach: what a particle can travel in this step plus a cell
        double vmax = 0;
        for (const auto& r : start) vmax = std::max(vmax, r.v.norm());
        MPI_Allreduce(MPI_IN_PLACE, &vmax, 1, MPI_DOUBLE, MPI_MAX, comm_);
        const scalar reach = vmax*runTime.deltaTValue() + largestCell_;
        exchange_->nearest_solid(solidFraction.cdata(), reach, solid);
    }
    // 2. whole DEM steps up to the fluid step (a sub-cycle longer than maxSubSteps is an
    // input mistake: a DEM step of the wrong unit or order of magnitude)
    const scalar maxSubSteps = 1e8;
    const scalar dtDem = lammps_->timestep();
    const scalar remaining = runTime.endTime().value() - runTime.value();
    const scalar dtFluid =
        remaining > 0 ? min(runTime.deltaTValue(), remaining) : runTime.deltaTValue();
    label n = fixedSubSteps_;
    scalar dtSub = dtDem;
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

    // the light each particle absorbs over the step (fixed, at mid-step)
    std::vector<double> light;
    shadeParticles(runTime, start, n*dtSub, light);
    // a laser heats the continuum past both: no upper bound then
    heated_ = laser_ != nullptr;

    std::unordered_map<std::int64_t, mc::FluidState> fluid;
    for (std::int64_t g = 0; g < exchange_->global_particles(); ++g)
    {
        if (!exchange_->global_inside(g)) continue;
        mc::FluidState& fs = fluid[exchange_->global_id(g)];
        fs = sampled[g].fluid;
        if (!solid.empty()) fs.solid = solid[g];
        if (!light.empty()) fs.heat_source = light[g];
        fs.thermal = thermal_;
    }
    lammps_->set_fluid(std::move(fluid));
    std::unordered_map<std::int64_t, double> lightOf;
    for (std::size_t g = 0; g < light.size(); ++g)
    {
        if (light[g] > 0) lightOf[exchange_->global_id(std::int64_t(g))] = light[g];
    }

    const std::int64_t before = lammps_->particles();
    const double tLmp0 = lammps_->time();
    exchangeSeconds_ += seconds() - t0;
    const double w0 = seconds();
    std::vector<mc::ExchangeRecord> records;
    const bool shortened = dtSub < dtDem*(1 - 1e-12);
    if (shortened) lammps_->set_timestep(dtSub);
    lammps_->advance(int(n), records);
    if (thermal_ && boundsSet_)
    {
        // particles inserted during the step (fix powder/insert temp) widen the range:
        // their temperature is as legitimate a bound as the old particles' (the others'
        // end temperatures lie between their start and their cells')
        scalar lo = GREAT, hi = -GREAT;
        for (const auto& r : records)
        {
            lo = min(lo, r.T);
            hi = max(hi, r.T);
        }
        Tlo_ = min(Tlo_, returnReduce(lo, minOp<scalar>()));
        Thi_ = max(Thi_, returnReduce(hi, maxOp<scalar>()));
    }
    // back to the DEM's own step unless the input changed it meanwhile (fix powder/dt)
    if (shortened && lammps_->timestep() == dtSub) lammps_->set_timestep(dtDem);
    lammpsSeconds_ += seconds() - w0;
    t0 = seconds();
    subSteps_ = n;
    const scalar elapsed = lammps_->time() - tLmp0;
    runTime.setDeltaT(elapsed, false);

    // particles lost by LAMMPS itself cannot be booked: refuse to go on
    std::int64_t nRecords = std::int64_t(records.size());
    MPI_Allreduce(MPI_IN_PLACE, &nRecords, 1, MPI_INT64_T, MPI_SUM, comm_);
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
    std::unordered_map<std::int64_t, double> startRadius;
    for (const auto& r : start) startRadius[r.id] = r.radius;
    for (auto& r : records)
    {
        if (r.mass > 0) continue;
        const auto radius = startRadius.find(r.id);
        if (radius != startRadius.end()) r.radius = max(r.radius, radius->second);
        const auto lit = lightOf.find(r.id);
        if (lit == lightOf.end()) continue;
        const double rest = lit->second*elapsed - r.external_heat;
        if (rest > 0)
        {
            r.external_heat += rest;
            r.enthalpy_out += rest;
        }
    }

    // 3./4. where each particle is now: inside -> deposit, outside -> outflow
    // keep the start-of-step location (for what the particles took), locate the end
    std::swap(exchange_, startExchange_);
    std::swap(located_, startLocated_);
    std::swap(haveLocated_, startHaveLocated_);
    relocate(shapesOf(records));
    inside_.clear();
    lost_.clear();
    // the melt (mass, its enthalpy and momentum) goes by the volume weights at the end of the
    // step, where it is; the heat and impulse the particles took come from the cells they
    // sampled at its start (heat by what each holds beyond the particle's temperature,
    // impulse by mass weights)
    std::vector<mc::Amounts> amounts;
    std::vector<std::int64_t> takers;
    std::vector<double> heat;
    std::vector<Eigen::Vector3d> impulse;
    std::vector<double> takerT;
    std::vector<std::int64_t> leaving;
    for (std::size_t i = 0; i < records.size(); ++i)
    {
        const mc::ExchangeRecord& r = records[i];
        if (exchange_->inside(i))
        {
            inside_.push_back(r);
            amounts.push_back(mc::make_amounts(r.mass_out, r.enthalpy_out, r.momentum_out));
            takers.push_back(r.id);
            heat.push_back(r.heat_absorbed);
            impulse.push_back(r.impulse_from_fluid);
            takerT.push_back(r.T);
        }
        else
        {
            lost_.push_back(r);
            amounts.push_back(mc::Amounts{});
            if (r.mass > 0) leaving.push_back(r.id);
        }
    }
    std::vector<mc::Amounts> deposited(std::size_t(nCells), mc::Amounts{});
    exchange_->deposit(amounts, deposited);
    startExchange_->deposit_taken(takers, heat, impulse, takerT, cells, deposited);

    const scalarField& V = mesh_.V();
    forAll(V, celli)
    {
        const mc::Amounts& a = deposited[celli];
        const scalar rate = 1/(V[celli]*elapsed);
        massSource_[celli] = a[mc::kMass]*rate;
        volumeSource_[celli] = massSource_[celli]/rhoMetal_;
        enthalpySource_[celli] = a[mc::kEnthalpy]*rate;
        momentumSource_[celli] = vector(a[mc::kMomX], a[mc::kMomY], a[mc::kMomZ])*rate;
    }

    // a cell cannot take more than its own volume of metal in one step: the volume
    // source would then have to push the gas out at more than a cell per step (the
    // fluid step collapses) and alpha overfills (the particle/cell size ratio is
    // beyond what the distribution model spreads)
    const scalar filled = gMax(volumeSource_.field())*elapsed;
    if (filled > 1 + 1e-6)
    {
        FatalErrorInFunction
            << "the molten metal of one step fills a cell " << filled << " times: distribution "
            << mc::to_string(model_) << " spreads each particle's melt over the cells of its "
            << "end-of-step shape (one cell for centre, at most 7 for neighbours; a particle "
            << "that melted away within the step by its start-of-step size), and particles larger "
            << "than the cells give them more metal than they hold. Use "
            << (model_ == mc::DistributionModel::Overlap ? "" : "distribution overlap, ")
            << "a shorter fluid step (maxDeltaT) so that large particles melt over several "
            << "steps, or coarser cells"
            << exit(FatalError);
    }

    std::int64_t nLeaving = std::int64_t(leaving.size());
    MPI_Allreduce(MPI_IN_PLACE, &nLeaving, 1, MPI_INT64_T, MPI_SUM, comm_);
    if (nLeaving)
    {
        lammps_->remove(leaving);
        Info<< "Particles: " << nLeaving << " left the mesh (booked as outflow)" << endl;
    }
    exchangeSeconds_ += seconds() - t0;

    Info<< "Particles: " << lammps_->particles() << " in " << n << " DEM steps of "
        << dtSub << " s; handed over " << gSum(massSource_.field()*V)*elapsed
        << " kg of metal" << endl;
}


void Foam::meltdem::particleCoupling::addMetal
(
    volScalarField& alpha1,
    volScalarField& alpha2
) const
{
    const scalar dt = mesh_.time().deltaTValue();
    alpha1.primitiveFieldRef() += volumeSource_.field()*dt;
    alpha1.correctBoundaryConditions();
    alpha2 = 1.0 - alpha1;
}


void Foam::meltdem::particleCoupling::book(const functionObjects::meltdemBalance& balance)
{
    const functionObjects::meltdemBalance::stepBudget& b = balance.lastStep();
    mc::ConservationLedger& L = *ledger_;
    L.begin_step(mesh_.time().value(), mesh_.time().deltaTValue());
    for (const auto& r : inside_) L.book_particle(r);
    for (const auto& r : lost_)
    {
        // outside the mesh nothing was deposited: its melt leaves with it
        mc::ExchangeRecord kept(r);
        kept.mass_out = 0;
        kept.enthalpy_out = 0;
        kept.momentum_out = Eigen::Vector3d::Zero();
        kept.heat_absorbed = 0;
        kept.impulse_from_fluid = Eigen::Vector3d::Zero();
        L.book_lost(kept);
        L.book(mc::kLost, mc::make_amounts(r.mass_out, r.enthalpy_out, r.momentum_out));
    }
    // powder from fix powder/insert: what was drawn this step is fed into the pending
    // store, from which the inserted particles come (they then appear in the records)
    mc::Amounts drawn, pending;
    lammps_->insertion_store(drawn, pending);
    if (Pstream::master())
    {
        for (int q = 0; q < mc::kComponents; ++q)
        {
            L.book(mc::kFeed, mc::Component(q), drawn[q] - drawnBefore_[q]);
        }
        L.book(mc::kPending, pending);
    }
    drawnBefore_ = drawn;
    checkEarlyLosses(drawn, pending);
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
                0, b.laserE - b.evapE,
                Eigen::Vector3d(b.gravityImpulse.x(), b.gravityImpulse.y(), b.gravityImpulse.z())
            )
        );
    }
    const mc::LedgerStep& s = L.end_step();

    // what the particles did this step (global sums), for plots and the heat split
    double sums[12] = {};  // the 12th: laser energy the particles absorbed
    for (const auto* list : {&inside_, &lost_})
    {
        for (const auto& r : *list)
        {
            sums[0] += r.mass;
            sums[1] += r.mass*r.h;
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
        o << mesh_.time().value() << ',' << mesh_.time().deltaTValue() << ',' << subSteps_
          << ',' << s.particles;
        for (int k = 0; k < 12; ++k) o << ',' << sums[k];
        o << ',' << exchangeSeconds_ << ',' << lammpsSeconds_ << '\n';
        o.flush();
    }
    Info<< "Particle ledger: continuum relative errors mass "
        << s.continuum_error[mc::kMass] << " enthalpy " << s.continuum_error[mc::kEnthalpy]
        << " momentum (" << s.continuum_error[mc::kMomX] << " "
        << s.continuum_error[mc::kMomY] << " " << s.continuum_error[mc::kMomZ] << ")"
        << nl << endl;
    checkBounded();
}


void Foam::meltdem::particleCoupling::checkEarlyLosses
(
    const mc::Amounts& drawn,
    const mc::Amounts& pending
)
{
    // within the first fluid steps, more than half of the inserted powder gone at once
    const label firstSteps = 100;
    const scalar share = 0.5;
    if (warnedLost_ || ++steps_ > firstSteps) return;
    double lost[2] = {0, 0};
    for (const auto& r : lost_)
    {
        if (r.id <= maxInitialId_) continue;
        lost[0] += r.mass + r.mass_out;
        lost[1] += 1;
    }
    MPI_Allreduce(MPI_IN_PLACE, lost, 2, MPI_DOUBLE, MPI_SUM, comm_);
    lostEarly_ += lost[0];
    lostEarlyCount_ += label(lost[1]);
    const scalar placed = placedEarly_ + drawn[mc::kMass] - pending[mc::kMass];
    if (lostEarlyCount_ >= 5 && lostEarly_ > share*placed)
    {
        warnedLost_ = true;
        const boundBox mb(distMesh_.globalBounds());
        WarningInFunction
            << lostEarlyCount_ << " of the grains fix powder/insert placed in the first "
            << steps_ << " fluid steps (" << lostEarly_ << " of " << placed << " kg, more than "
            << 100*share << " %) left the mesh at once and are booked lost: is the insertion "
            << "region inside the mesh " << mb << "? Grains outside the mesh are not coupled"
            << endl;
    }
}


void Foam::meltdem::particleCoupling::checkBounded() const
{
    if (!thermal_ || !boundsSet_) return;
    const volScalarField& T = mesh_.lookupObject<volScalarField>("T");
    const scalar Tmin = min(T).value(), Tmax = max(T).value();
    // 1 % of the range: what the bounded (TVD) schemes and the solver tolerance may leave
    const scalar out = mc::temperature_overshoot(Tlo_, Thi_, Tmin, Tmax, 1e-2, !heated_);
    if (out > 0)
    {
        // the cell furthest outside the range, and how far the particles' heat alone moved it
        // (the rest is the continuum's own solve: flow, surface forces, laser, the melt's
        // volume source), so that a user sees which of the two left the range
        const scalarField& Tc = T.primitiveField();
        const scalarField& T0 = T.oldTime().primitiveField();
        const volScalarField& rhoCp = mesh_.lookupObject<volScalarField>("rhoCp");
        const scalar dt = mesh_.time().deltaTValue();
        struct { double excess; int rank; } worst{-1.0, 0};
        label worstCell = -1;
        forAll(Tc, celli)
        {
            const scalar e = max(Tlo_ - Tc[celli], heated_ ? 0.0 : Tc[celli] - Thi_);
            if (e > worst.excess) worst.excess = e, worstCell = celli;
        }
        MPI_Comm_rank(comm_, &worst.rank);
        const int me = worst.rank;
        MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_);
        double cell[6] = {0, 0, 0, 0, 0, 0};
        if (me == worst.rank && worstCell >= 0)
        {
            const point& x = mesh_.C()[worstCell];
            cell[0] = T0[worstCell], cell[1] = Tc[worstCell];
            cell[2] = enthalpySource_[worstCell]*dt/max(rhoCp[worstCell], VSMALL);
            cell[3] = x.x(), cell[4] = x.y(), cell[5] = x.z();
        }
        MPI_Bcast(cell, 6, MPI_DOUBLE, worst.rank, comm_);
        FatalErrorInFunction
            << "the continuum temperature left [" << Tlo_ << ", " << Thi_ << "] K, the range "
            << "of continuum and particles before the step and of the particles after it "
            << "(T min/max now " << Tmin << ", "
            << Tmax << " K): the particles exchanged more heat over the fluid step ("
            << mesh_.time().deltaTValue() << " s, fluid frozen) than their cells hold. "
            << "The worst cell's heat capacity over its particles' conductance is "
            << exchangeTime_ << " s: lower maxDeltaT (controlDict) or demStepsPerFluidStep "
            << "towards it, or spread the exchange over more cells (distribution overlap "
            << "or neighbours, coarser cells). The cell furthest out, at (" << cell[3] << " "
            << cell[4] << " " << cell[5] << "), went from " << cell[0] << " to " << cell[1]
            << " K, of which the particles' exchange about " << cell[2] << " K"
            << (mag(cell[2]) < 0.1*mag(cell[1] - cell[0])
                ? ": the rest came from the continuum's own solve (flow, surface forces, "
                  "laser, the displacement by the melt's volume), which maxDeltaT and maxCo "
                  "limit, and whose convection of T energyControls maxThermalCo bounds"
                : "")
            << exit(FatalError);
    }
}


void Foam::meltdem::particleCoupling::shadeParticles
(
    const Time& runTime,
    const std::vector<mc::ExchangeRecord>& start,
    scalar dtPlanned,
    std::vector<double>& absorbed
)
{
    absorbed.clear();
    if (!laser_) return;
    const scalar tMid = runTime.value() + 0.5*dtPlanned;
    if (!laserShadow_ || !laser_->on(tMid) || laser_->power() <= 0)
    {
        laser_->setShadow({}, 1);
        return;
    }
    mc::GaussianBeam beam;
    beam.power = laser_->power();
    beam.absorptivity = laser_->absorptivity();
    beam.radius = laser_->radius();
    const point c(laser_->position(tMid));
    const vector& e = laser_->direction();
    beam.centre = Eigen::Vector3d(c.x(), c.y(), c.z());
    beam.direction = Eigen::Vector3d(e.x(), e.y(), e.z());
    // particles that melted away in the last step (deleted at the next DEM step) cast
    // no shadow any more
    std::vector<mc::BeamParticle> local;
    std::vector<std::size_t> solid;
    local.reserve(start.size());
    for (std::size_t i = 0; i < start.size(); ++i)
    {
        if (start[i].mass > 0)
        {
            local.push_back({start[i].x, start[i].radius});
            solid.push_back(i);
        }
    }
    shadow_ = mc::shade_particles(comm_, beam, local);

    // by global index (rank order, as the exchange numbers them)
    const std::size_t offset = exchange_->local_offset();
    absorbed.assign(std::size_t(exchange_->global_particles()), 0.0);
    for (std::size_t k = 0; k < solid.size(); ++k)
    {
        absorbed[offset + solid[k]] = shadow_.absorbed[k];
    }
    if (!absorbed.empty())
    {
        MPI_Allreduce(MPI_IN_PLACE, absorbed.data(), int(absorbed.size()), MPI_DOUBLE, MPI_SUM, comm_);
    }
    const mc::ShadowResult* result = &shadow_;
    laser_->setShadow
    (
        [result](const point& p, const scalar footprint)
        {
            return scalar(mc::transmitted_fraction(*result, Eigen::Vector3d(p.x(), p.y(), p.z()), footprint));
        },
        shadow_.transmitted_power/beam.power
    );
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
    MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_MIN, comm_);
    if (same) return;
    exchange_->locate(shapes);
    located_ = shapes;
    haveLocated_ = true;
}
