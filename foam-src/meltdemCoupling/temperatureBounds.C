#include "temperatureBounds.H"

#include "meltdem/coupling/particle_melting.h"

namespace mc = ::meltdem::coupling;

Foam::meltdem::temperatureBounds::temperatureBounds(const fvMesh& mesh, MPI_Comm comm)
:
    mesh_(mesh),
    comm_(comm),
    Tlo_(0),
    Thi_(0),
    exchangeTime_(GREAT),
    fixedStepOverrun_(0),
    fixedStep_(0),
    fixedSubSteps_(0),
    set_(false),
    heated_(false),
    warnedLongStep_(false)
{}


void Foam::meltdem::temperatureBounds::start
(
    const volScalarField& T,
    const scalar Tplo,
    const scalar Tphi,
    const scalar exchangeTime
)
{
    exchangeTime_ = exchangeTime;
    const scalar dt = mesh_.time().deltaTValue();
    if (!warnedLongStep_ && dt > exchangeTime_)
    {
        // the two-body exchange stays bounded, but a parcel that empties within the step
        // delivers about C/(G dt) of the rate the unbounded fluid would
        WarningInFunction
            << "the fluid step " << dt << " s is longer than the worst cell's heat capacity "
            << "over its particles' conductance, C/G = " << exchangeTime_ << " s: the exchange "
            << "stays bounded, but those particles take at most what their cells hold per step, "
            << "about C/(G dt) = " << exchangeTime_/dt << " of the rate of an unbounded fluid. "
            << "For the rate, use particles { heatExchange implicit; } (the energy solve takes "
            << "the heat from the cells) or lower maxDeltaT (controlDict) or demStepsPerFluidStep "
            << "towards C/G. (Warned once per run.)" << endl;
        warnedLongStep_ = true;
    }
    Tlo_ = min(returnReduce(Tplo, minOp<scalar>()), min(T).value());
    Thi_ = max(returnReduce(Tphi, maxOp<scalar>()), max(T).value());
    set_ = true;
}


void Foam::meltdem::temperatureBounds::widen(const std::vector<mc::ExchangeRecord>& records)
{
    if (!set_) return;
    scalar lo = GREAT, hi = -GREAT;
    for (const auto& r : records)
    {
        lo = min(lo, r.T);
        hi = max(hi, r.T);
    }
    Tlo_ = min(Tlo_, returnReduce(lo, minOp<scalar>()));
    Thi_ = max(Thi_, returnReduce(hi, maxOp<scalar>()));
}


void Foam::meltdem::temperatureBounds::check(const volScalarField::Internal& enthalpySource) const
{
    if (!set_) return;
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
            cell[2] = enthalpySource[worstCell]*dt/max(rhoCp[worstCell], VSMALL);
            cell[3] = x.x(), cell[4] = x.y(), cell[5] = x.z();
        }
        MPI_Bcast(cell, 6, MPI_DOUBLE, worst.rank, comm_);
        FatalErrorInFunction
            << "the continuum temperature left [" << Tlo_ << ", " << Thi_ << "] K, the range "
            << "of continuum and particles before the step and of the particles after it "
            << "(T min/max now " << Tmin << ", "
            << Tmax << " K). ";
        if (exchangeTime_ < 0.5*GREAT)
        {
            FatalError
                << "The particles exchanged more heat over the fluid step ("
                << mesh_.time().deltaTValue() << " s, fluid frozen) than their cells hold. "
                << "The worst cell's heat capacity over its particles' conductance is "
                << exchangeTime_ << " s: lower maxDeltaT (controlDict) or demStepsPerFluidStep "
                << "towards it, or spread the exchange over more cells (distribution overlap "
                << "or neighbours, coarser cells). ";
        }
        else
        {
            FatalError
                << "The particles' heat (heatExchange implicit, in the energy solve) cannot "
                << "take a cell out of that range; the continuum's own solve did (fluid step "
                << mesh_.time().deltaTValue() << " s): lower maxDeltaT or maxCo. ";
        }
        FatalError
            << "The cell furthest out, at (" << cell[3] << " "
            << cell[4] << " " << cell[5] << "), went from " << cell[0] << " to " << cell[1]
            << " K, of which the particles' exchange about " << cell[2] << " K"
            << (mag(cell[2]) < 0.1*mag(cell[1] - cell[0])
                ? ": the rest came from the continuum's own solve (flow, surface forces, "
                  "laser, the displacement by the melt's volume), which maxDeltaT and maxCo "
                  "limit, and whose convection of T energyControls maxThermalCo bounds"
                : "");
        if (fixedStepOverrun_ > 1 + 1e-9)
        {
            FatalError
                << ". This fluid step was fixed by demStepsPerFluidStep " << fixedSubSteps_
                << " at " << fixedStep_ << " s, " << fixedStepOverrun_ << " times the step "
                << "maxCo, maxAlphaCo and maxDeltaT allowed: use demStepsPerFluidStep auto, "
                << "or a smaller N";
        }
        FatalError << exit(FatalError);
    }
}
