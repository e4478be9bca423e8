#include "particleCommunicator.H"

Foam::meltdem::particleCommunicator::particleCommunicator()
:
    comm_(MPI_COMM_NULL),
    ownMpi_(false)
{
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
    {
        MPI_Init(nullptr, nullptr);
        ownMpi_ = true;
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
}


Foam::meltdem::particleCommunicator::~particleCommunicator()
{
    MPI_Comm_free(&comm_);
    if (ownMpi_) MPI_Finalize();
}
