#include "particleDeposition.H"

namespace mc = ::meltdem::coupling;

Foam::meltdem::particleDeposition::particleDeposition
(
    const fvMesh& mesh,
    const scalar rhoMetal,
    const mc::DistributionModel model
)
:
    mesh_(mesh),
    rhoMetal_(rhoMetal),
    model_(model),
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
    )
{}


void Foam::meltdem::particleDeposition::deposit
(
    const std::vector<mc::ExchangeRecord>& records,
    mc::ParallelExchange& end,
    mc::ParallelExchange& start,
    const mc::CellFluidFields& cells,
    const scalar elapsed,
    std::vector<mc::ExchangeRecord>& inside,
    std::vector<mc::ExchangeRecord>& lost,
    std::vector<std::int64_t>& leaving
)
{
    inside.clear();
    lost.clear();
    leaving.clear();
    // the melt (mass, its enthalpy and momentum) goes by the volume weights at the end of the
    // step, where it is; the heat and impulse the particles took come from the cells they
    // sampled at its start (heat by what each holds beyond the particle's temperature,
    // impulse by mass weights), also for a particle that left the mesh during the step
    std::vector<mc::Amounts> amounts;
    std::vector<std::int64_t> takers;
    std::vector<int> locatedBy;
    std::vector<double> heat;
    std::vector<Eigen::Vector3d> impulse;
    std::vector<double> takerT;
    for (std::size_t i = 0; i < records.size(); ++i)
    {
        const mc::ExchangeRecord& r = records[i];
        takers.push_back(r.id);
        locatedBy.push_back(r.located_by);
        heat.push_back(r.heat_absorbed);
        impulse.push_back(r.impulse_from_fluid);
        takerT.push_back(r.T);
        if (end.inside(i))
        {
            inside.push_back(r);
            amounts.push_back(mc::make_amounts(r.mass_out, r.enthalpy_out, r.momentum_out));
        }
        else
        {
            lost.push_back(r);
            amounts.push_back(mc::Amounts{});
            if (r.mass > 0) leaving.push_back(r.id);
        }
    }
    std::vector<mc::Amounts> deposited(std::size_t(mesh_.nCells()), mc::Amounts{});
    end.deposit(amounts, deposited);
    start.deposit_taken(takers, locatedBy, heat, impulse, takerT, cells, deposited);

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
}


void Foam::meltdem::particleDeposition::addMetal
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


void Foam::meltdem::particleDeposition::clear()
{
    massSource_.field() = 0;
    volumeSource_.field() = 0;
    enthalpySource_.field() = 0;
    momentumSource_.field() = vector::zero;
}
