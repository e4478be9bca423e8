#include "caseCheckpoint.H"

#include "OSspecific.H"
#include "Pstream.H"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sys/statvfs.h>

Foam::meltdem::caseCheckpoint::caseCheckpoint(const Time& runTime)
:
    runTime_(runTime)
{}


Foam::fileName Foam::meltdem::caseCheckpoint::dir(const Time& runTime, const word& timeName)
{
    return runTime.globalPath()/"meltdemRestart"/timeName;
}


double Foam::meltdem::caseCheckpoint::bytesUnder(const fileName& path)
{
    double bytes = 0;
    for (const fileName& f : readDir(path, fileName::FILE)) bytes += fileSize(path/f);
    for (const fileName& d : readDir(path, fileName::DIRECTORY)) bytes += bytesUnder(path/d);
    return bytes;
}


Foam::word Foam::meltdem::caseCheckpoint::latestComplete() const
{
    const fileName root(runTime_.globalPath()/"meltdemRestart");
    word latest;
    scalar tLatest = -GREAT;
    for (const fileName& t : readDir(root, fileName::DIRECTORY))
    {
        scalar v;
        if (readScalar(t, v) && v > tLatest && isFile(root/t/"complete"))
        {
            latest = t;
            tLatest = v;
        }
    }
    return latest;
}


void Foam::meltdem::caseCheckpoint::written(const bool writeOk)
{
    if (!runTime_.writeTime()) return;
    const word t(runTime_.timeName());
    // A write that met a full disk is cut short without an error from OpenFOAM's
    // streams; a disk left with less room than this write took is taken as that
    const fileName timeDir(runTime_.path()/t);
    double need = bytesUnder(timeDir);
    if (Pstream::master()) need += bytesUnder(dir(runTime_, t));
    struct statvfs fs;
    double avail = -1;
    if (::statvfs(timeDir.c_str(), &fs) == 0) avail = double(fs.f_bavail)*double(fs.f_frsize);
    int full = (avail >= 0 && avail < need) ? 1 : 0;
    int failed = writeOk ? 0 : 1;
    reduce(full, maxOp<int>());
    reduce(failed, maxOp<int>());
    if (full || failed)
    {
        FatalErrorInFunction
            << (full ? "the disk holding the case is full" : "the time folder could not be written")
            << ": writing t = " << t << " s (" << timeDir << ", " << need << " bytes) left "
            << (avail >= 0 ? std::to_string(static_cast<long long>(avail)) : std::string("unknown"))
            << " bytes free. This write time is incomplete and not a checkpoint; "
            << (latestComplete().empty()
                ? string("no checkpoint is complete yet")
                : "the last complete checkpoint, t = " + latestComplete() + " s, is kept")
            << ". Free disk space, then resume with: meltdem run " << runTime_.globalPath()
            << " --resume" << exit(FatalError);
    }
    due_ = t;
}


void Foam::meltdem::caseCheckpoint::markComplete()
{
    if (due_.empty()) return;
    if (Pstream::master())
    {
        const fileName d(dir(runTime_, due_));
        mkDir(d);
        std::ofstream os(d/"complete", std::ios::trunc);
        os << due_ << '\n';
        os.close();
        if (!os)
        {
            FatalErrorInFunction
                << "cannot write " << d/"complete" << ": " << std::strerror(errno)
                << " (the disk holding the case is full?)" << exit(FatalError);
        }
    }
    due_.clear();
}
