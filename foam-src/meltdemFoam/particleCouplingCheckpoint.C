// particleCoupling checkpoints: at every write time both codes save their state at the
// same simulated time, so a run stopped mid-way resumes from its last write time and ends
// with the ledger totals of an uninterrupted run (issue 7). The continuum's state is the
// time folder OpenFOAM writes; the particles' is a LAMMPS restart; the ledger's (previous
// and cumulative totals) a text file with exact doubles. 'complete' is written last: a
// checkpoint without it was cut off and is never resumed from (caseCheckpoint.H).
#include "particleCoupling.H"
#include "caseCheckpoint.H"

#include "OSspecific.H"
#include "Time.H"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mc = ::meltdem::coupling;


Foam::fileName Foam::meltdem::particleCoupling::checkpointDir(const word& timeName) const
{
    return caseCheckpoint::dir(mesh_.time(), timeName);
}


bool Foam::meltdem::particleCoupling::readCheckpoint
(
    double& lammpsTime,
    std::string& ledgerState
) const
{
    const fileName dir(checkpointDir(mesh_.time().timeName()));
    if (!isFile(dir/"complete")) return false;
    std::ifstream in(dir/"state");
    std::string key, value;
    if (!(in >> key >> value) || key != "lammps_time")
    {
        FatalErrorInFunction
            << "the checkpoint " << dir/"state" << " is unreadable (no lammps_time): "
            << "remove " << dir << " to start this time afresh, or resume from an "
            << "earlier write time" << exit(FatalError);
    }
    lammpsTime = std::strtod(value.c_str(), nullptr);
    std::ostringstream rest;
    rest << in.rdbuf();
    ledgerState = rest.str();
    if (!isFile(dir/::meltdem::LammpsCouplingHost::kRestartFile))
    {
        FatalErrorInFunction
            << "the checkpoint " << dir << " has no "
            << ::meltdem::LammpsCouplingHost::kRestartFile << exit(FatalError);
    }
    return true;
}


void Foam::meltdem::particleCoupling::resumeParticlesCsv
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


void Foam::meltdem::particleCoupling::write()
{
    const Time& runTime = mesh_.time();
    const fileName dir(checkpointDir(runTime.timeName()));
    const fileName dumps(runTime.globalPath()/"particles");
    if (Pstream::master())
    {
        mkDir(dir);
        mkDir(dumps);
        rm(dir/"complete");
    }
    MPI_Barrier(comm_);
    // the particles ParaView shows beside this time's fields
    lammps_->write_particles(dumps/(runTime.timeName() + ".dump"));
    try
    {
        lammps_->write_checkpoint(dir);
    }
    catch (const ::meltdem::LammpsSetupError& e)
    {
        FatalErrorInFunction << e.what() << exit(FatalError);
    }
    if (Pstream::master())
    {
        std::ostringstream state;
        char t[64];
        std::snprintf(t, sizeof t, "%a", lammps_->time());
        state << "lammps_time " << t << '\n';
        ledger_->save_state(state);
        std::ofstream os(dir/"state", std::ios::trunc);
        os << state.str();
        os.close();
        if (!os)
        {
            FatalErrorInFunction
                << "cannot write the checkpoint " << dir/"state" << ": "
                << std::strerror(errno) << " (the disk holding the case is full?)"
                << exit(FatalError);
        }
    }
    // 'complete' follows once the whole write time is written (caseCheckpoint)
    MPI_Barrier(comm_);
}
