#include "particleSampling.H"

#include "meltdem/coupling/particle_melting.h"

namespace mc = ::meltdem::coupling;

Foam::meltdem::particleSampling::particleSampling
(
    const fvMesh& mesh,
    MPI_Comm comm,
    const bool thermal,
    const bool laserShadow
)
:
    mesh_(mesh),
    comm_(comm),
    thermal_(thermal),
    laserShadow_(laserShadow),
    largestCell_(Foam::cbrt(gMax(mesh.V().field()))),
    laser_(nullptr),
    wasSolid_
    (
        IOobject
        (
            "wasSolidMetal",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        mesh,
        dimensionedScalar("unknown", dimless, -1.0)
    )
{
    IOobject io(wasSolid_.name(), mesh.time().timeName(), mesh, IOobject::MUST_READ);
    if (io.typeHeaderOk<volScalarField>(true))
    {
        wasSolid_ = volScalarField(io, mesh);
        wasSolid_.writeOpt() = IOobject::AUTO_WRITE;
    }
}


::meltdem::coupling::CellFluidFields Foam::meltdem::particleSampling::cellFields
(
    const fluidFields& f,
    const scalarField& cp
)
{
    return mc::CellFluidFields
    {
        f.T.primitiveField().cdata(),
        f.kappa.primitiveField().cdata(),
        f.rho.primitiveField().cdata(),
        f.mu.primitiveField().cdata(),
        cp.cdata(),
        reinterpret_cast<const double*>(f.U.primitiveField().cdata()),
        f.alphaMetal.primitiveField().cdata(),
        f.liquidFraction.primitiveField().cdata(),
        f.T.mesh().V().cdata()
    };
}


void Foam::meltdem::particleSampling::sample
(
    mc::ParallelExchange& exchange,
    const mc::CellFluidFields& cells,
    const fluidFields& f,
    const std::vector<mc::ExchangeRecord>& start,
    temperatureBounds& bounds,
    std::vector<mc::SampledFluid>& sampled
) const
{
    exchange.sample(cells, sampled);
    if (!thermal_) return;
    // the range no exchange may leave, and the worst cell's C/G for the message
    std::vector<double> g(start.size(), 0.0);
    scalar Tplo = GREAT, Tphi = -GREAT;
    for (std::size_t i = 0; i < start.size(); ++i)
    {
        if (!exchange.inside(i)) continue;
        g[i] = mc::particle_conductance
        (
            sampled[i].fluid, 2*start[i].radius, start[i].v.data()
        );
        Tplo = min(Tplo, start[i].T);
        Tphi = max(Tphi, start[i].T);
    }
    const scalarField& V = mesh_.V();
    std::vector<double> conductance(std::size_t(V.size()), 0.0);
    exchange.deposit(g, conductance);
    std::vector<double> heatCapacity(V.size());
    forAll(V, celli)
    {
        heatCapacity[celli] = f.rhoCp[celli]*V[celli];
    }
    const scalar exchangeTime = returnReduce
    (
        mc::heat_exchange_time(heatCapacity.data(), conductance.data(), V.size()),
        minOp<scalar>()
    );
    bounds.start(f.T, Tplo, Tphi, implicitHeat_ ? GREAT : exchangeTime);
}


void Foam::meltdem::particleSampling::solidSurfaces
(
    mc::ParallelExchange& exchange,
    const fluidFields& f,
    const std::vector<mc::ExchangeRecord>& start,
    const scalar dt,
    std::vector<mc::SolidSurface>& solid
)
{
    const scalarField solidFraction
    (
        f.alphaMetal.primitiveField()*(1 - f.liquidFraction.primitiveField())
    );
    // reach: what a particle can travel in this step plus a cell
    double vmax = 0;
    for (const auto& r : start) vmax = std::max(vmax, r.v.norm());
    MPI_Allreduce(MPI_IN_PLACE, &vmax, 1, MPI_DOUBLE, MPI_MAX, comm_);
    const scalar reach = vmax*dt + largestCell_;
    std::vector<Eigen::Vector3d> velocity;
    velocity.reserve(start.size());
    for (const auto& r : start) velocity.push_back(r.v);
    exchange.nearest_solid
    (
        solidFraction.cdata(), reach, solid, wasSolid_.primitiveField().cdata(),
        &velocity
    );
    // the mask, not the fraction: exact when written and read back
    wasSolid_.primitiveFieldRef() = pos0(solidFraction - 0.5);
    wasSolid_.writeOpt() = IOobject::AUTO_WRITE;
}


void Foam::meltdem::particleSampling::shade
(
    const Time& runTime,
    const std::vector<mc::ExchangeRecord>& start,
    const scalar dtPlanned,
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
    mc::shade_particles(comm_, beam, local, {}, shadow_);

    absorbed.assign(start.size(), 0.0);
    for (std::size_t k = 0; k < solid.size(); ++k)
    {
        absorbed[solid[k]] = shadow_.absorbed[k];
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


void Foam::meltdem::particleSampling::fluidStates
(
    const mc::ParallelExchange& exchange,
    const std::vector<mc::ExchangeRecord>& start,
    const std::vector<mc::SampledFluid>& sampled,
    const std::vector<mc::SolidSurface>& solid,
    const std::vector<double>& light,
    std::vector<std::int64_t>& ids,
    std::vector<mc::FluidState>& states
) const
{
    ids.clear();
    states.clear();
    ids.reserve(start.size());
    states.reserve(start.size());
    for (std::size_t i = 0; i < start.size(); ++i)
    {
        if (!exchange.inside(i)) continue;
        ids.push_back(start[i].id);
        mc::FluidState fs = sampled[i].fluid;
        if (!solid.empty()) fs.solid = solid[i];
        if (!light.empty()) fs.heat_source = light[i];
        fs.thermal = thermal_;
        fs.implicit_heat = thermal_ && implicitHeat_;
        if (given_) fs.mass = fs.capacity = 0;
        states.push_back(fs);
    }
}
