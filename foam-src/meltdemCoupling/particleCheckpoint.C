#include "particleCheckpoint.H"

#include "caseCheckpoint.H"
#include "OSspecific.H"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

Foam::meltdem::particleCheckpoint::particleCheckpoint(const Time& runTime, MPI_Comm comm)
:
    runTime_(runTime),
    comm_(comm)
{}


Foam::fileName Foam::meltdem::particleCheckpoint::dir(const word& timeName) const
{
    return caseCheckpoint::dir(runTime_, timeName);
}


bool Foam::meltdem::particleCheckpoint::read
(
    double& lammpsTime,
    std::string& ledgerState
) const
{
    const fileName d(dir(runTime_.timeName()));
    if (!isFile(d/"complete")) return false;
    std::ifstream in(d/"state");
    std::string key, value;
    if (!(in >> key >> value) || key != "lammps_time")
    {
        FatalErrorInFunction
            << "the checkpoint " << d/"state" << " is unreadable (no lammps_time): "
            << "remove " << d << " to start this time afresh, or resume from an "
            << "earlier write time" << exit(FatalError);
    }
    lammpsTime = std::strtod(value.c_str(), nullptr);
    std::ostringstream rest;
    rest << in.rdbuf();
    ledgerState = rest.str();
    if (!isFile(d/::meltdem::LammpsCouplingHost::kRestartFile))
    {
        FatalErrorInFunction
            << "the checkpoint " << d << " has no "
            << ::meltdem::LammpsCouplingHost::kRestartFile << exit(FatalError);
    }
    return true;
}


void Foam::meltdem::particleCheckpoint::write
(
    ::meltdem::LammpsCouplingHost& lammps,
    const particleLedgerOutput& ledger
) const
{
    const fileName d(dir(runTime_.timeName()));
    const fileName dumps(runTime_.globalPath()/"particles");
    if (Pstream::master())
    {
        mkDir(d);
        mkDir(dumps);
        rm(d/"complete");
    }
    MPI_Barrier(comm_);
    // the particles ParaView shows beside this time's fields
    lammps.write_particles(dumps/(runTime_.timeName() + ".dump"));
    try
    {
        lammps.write_checkpoint(d);
    }
    catch (const ::meltdem::LammpsSetupError& e)
    {
        FatalErrorInFunction << e.what() << exit(FatalError);
    }
    if (Pstream::master())
    {
        std::ostringstream state;
        char t[64];
        std::snprintf(t, sizeof t, "%a", lammps.time());
        state << "lammps_time " << t << '\n';
        ledger.saveState(state);
        std::ofstream os(d/"state", std::ios::trunc);
        os << state.str();
        os.close();
        if (!os)
        {
            FatalErrorInFunction
                << "cannot write the checkpoint " << d/"state" << ": "
                << std::strerror(errno) << " (the disk holding the case is full?)"
                << exit(FatalError);
        }
    }
    // 'complete' follows once the whole write time is written (caseCheckpoint)
    MPI_Barrier(comm_);
}
