#include "insertionLossWatch.H"

namespace mc = ::meltdem::coupling;

Foam::meltdem::insertionLossWatch::insertionLossWatch
(
    const ::meltdem::LammpsCouplingHost& lammps,
    MPI_Comm comm
)
:
    comm_(comm),
    maxInitialId_(0),
    placedBefore_(0),
    lost_(0),
    lostCount_(0),
    steps_(0),
    warned_(false)
{
    mc::Amounts drawn, pending;
    lammps.insertion_store(drawn, pending);
    placedBefore_ = drawn[mc::kMass] - pending[mc::kMass];
    std::vector<mc::ExchangeRecord> now;
    lammps.local_particles(now);
    for (const auto& r : now) maxInitialId_ = std::max(maxInitialId_, r.id);
    MPI_Allreduce(MPI_IN_PLACE, &maxInitialId_, 1, MPI_INT64_T, MPI_MAX, comm_);
}


void Foam::meltdem::insertionLossWatch::check
(
    const std::vector<mc::ExchangeRecord>& lost,
    const ::meltdem::LammpsCouplingHost& lammps,
    const boundBox& mesh
)
{
    const label firstSteps = 100;
    const scalar share = 0.5;
    if (warned_ || ++steps_ > firstSteps) return;
    double gone[2] = {0, 0};
    for (const auto& r : lost)
    {
        if (r.id <= maxInitialId_) continue;
        gone[0] += r.mass + r.mass_out;
        gone[1] += 1;
    }
    MPI_Allreduce(MPI_IN_PLACE, gone, 2, MPI_DOUBLE, MPI_SUM, comm_);
    lost_ += gone[0];
    lostCount_ += label(gone[1]);
    mc::Amounts drawn, pending;
    lammps.insertion_store(drawn, pending);
    const scalar placed = drawn[mc::kMass] - pending[mc::kMass] - placedBefore_;
    if (lostCount_ >= 5 && lost_ > share*placed)
    {
        warned_ = true;
        WarningInFunction
            << lostCount_ << " of the grains fix powder/insert placed in the first "
            << steps_ << " fluid steps (" << lost_ << " of " << placed << " kg, more than "
            << 100*share << " %) left the mesh at once and are booked lost: is the insertion "
            << "region inside the mesh " << mesh << "? Grains outside the mesh are not coupled"
            << endl;
    }
}
