#include "particleHeatExchange.H"

#include "meltdem/coupling/particle_melting.h"

#include <unordered_map>

namespace mc = ::meltdem::coupling;

Foam::meltdem::particleHeatExchange::particleHeatExchange
(
    const fvMesh& mesh,
    const scalar Tmelt
)
:
    mesh_(mesh),
    Tmelt_(Tmelt),
    sinkCoeff_
    (
        IOobject("particleHeatSinkCoeff", mesh.time().timeName(), mesh),
        mesh, dimensionedScalar("zero", dimPower/dimVolume/dimTemperature, 0)
    ),
    sinkSource_
    (
        IOobject("particleHeatSinkSource", mesh.time().timeName(), mesh),
        mesh, dimensionedScalar("zero", dimPower/dimVolume, 0)
    ),
    dt_(0)
{}


void Foam::meltdem::particleHeatExchange::prepare
(
    const std::vector<mc::ExchangeRecord>& records,
    const mc::ParallelExchange& exchange,
    const volScalarField& T,
    const scalar dt
)
{
    dt_ = dt;
    coeff_.assign(records.size(), 0);
    Tp_.assign(records.size(), 0);
    ids_.resize(records.size());
    // the cells' mean T before the step: a particle at its melting point that they heat
    // takes the whole G dt (T - Tm) (phi = 1: its latent heat holds it at Tm; its sensible
    // capacity alone would let a shrinking remnant take ever less); what melts it beyond
    // goes on with its melt
    std::vector<double> before;
    exchange.weighted_mean(T.primitiveField().cdata(), before);
    std::vector<mc::Amounts> sinks(records.size(), mc::Amounts{});
    for (std::size_t i = 0; i < records.size(); ++i)
    {
        const mc::ExchangeRecord& r = records[i];
        ids_[i] = r.id;
        Tp_[i] = r.T;
        if (!exchange.inside(i) || !(r.mass > 0) || !(r.conductance > 0) || !(r.heat_capacity > 0))
        {
            continue;
        }
        const bool melting = r.T >= Tmelt_ && before[i] > r.T;
        coeff_[i] =
            r.conductance*(melting ? 1 : mc::relaxation_factor(dt*r.conductance/r.heat_capacity));
        sinks[i][0] = coeff_[i];
        sinks[i][1] = coeff_[i]*r.T;
    }
    std::vector<mc::Amounts> cells(std::size_t(mesh_.nCells()), mc::Amounts{});
    exchange.deposit(sinks, cells);
    const scalarField& V = mesh_.V();
    forAll(V, celli)
    {
        sinkCoeff_[celli] = cells[celli][0]/V[celli];
        sinkSource_[celli] = cells[celli][1]/V[celli];
    }
    Tsolved_.clear();
}


void Foam::meltdem::particleHeatExchange::settle
(
    const mc::ParallelExchange& exchange,
    std::vector<mc::ExchangeRecord>& inside,
    ::meltdem::LammpsCouplingHost& lammps
) const
{
    if (Tsolved_.size() != mesh_.nCells())
    {
        FatalErrorInFunction
            << "particles { heatExchange implicit; } needs the energy equation solved this step"
            << exit(FatalError);
    }
    std::vector<double> mean;
    exchange.weighted_mean(Tsolved_.cdata(), mean);
    std::unordered_map<std::int64_t, double> heatOf;
    std::vector<std::int64_t> tags;
    std::vector<double> heat;
    for (std::size_t i = 0; i < coeff_.size(); ++i)
    {
        if (coeff_[i] <= 0) continue;
        const double Q = dt_*coeff_[i]*(mean[i] - Tp_[i]);
        heatOf[ids_[i]] = Q;
        tags.push_back(ids_[i]);
        heat.push_back(Q);
    }
    for (auto& r : inside)
    {
        const auto it = heatOf.find(r.id);
        r.heat_absorbed = it == heatOf.end() ? 0 : it->second;
        r.heat_owed += r.heat_absorbed;
    }
    lammps.set_heat_owed(tags, heat);
}
