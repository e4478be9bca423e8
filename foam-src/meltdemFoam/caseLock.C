#include "caseLock.H"

#include "OSspecific.H"
#include "Pstream.H"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <string>
#include <sys/file.h>
#include <unistd.h>

namespace
{

std::string readAll(int fd)
{
    std::string text;
    char buf[512];
    ::lseek(fd, 0, SEEK_SET);
    for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) text.append(buf, std::size_t(n));
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

} // End anonymous namespace


Foam::meltdem::caseLock::caseLock(const Time& runTime)
:
    fd_(-1)
{
    if (!Pstream::master()) return;
    const fileName lockFile(runTime.globalPath()/".meltdem.lock");
    const char* held = std::getenv("MELTDEM_CASE_LOCK");
    if (held && fileName(held) == lockFile)
    {
        return;  // `meltdem run` holds it for this job
    }
    fd_ = ::open(lockFile.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
    {
        FatalErrorInFunction
            << "cannot open the case lock " << lockFile << ": " << std::strerror(errno)
            << exit(FatalError);
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
    {
        const std::string holder(readAll(fd_));
        FatalErrorInFunction
            << "another run is using the case " << runTime.globalPath() << " ("
            << (holder.empty() ? std::string("holder unknown") : holder) << "): one run per case "
            << "folder. Wait for it to end or stop it; copy the case to run it twice"
            << exit(FatalError);
    }
    const std::string stale(readAll(fd_));
    if (!stale.empty())
    {
        Info<< "Case lock: taken over from a run that ended without releasing it ("
            << stale << ")" << endl;
    }
    char host[256] = "";
    ::gethostname(host, sizeof host - 1);
    char when[64] = "";
    const std::time_t now = std::time(nullptr);
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%S", std::localtime(&now));
    const std::string me
    (
        "pid " + std::to_string(::getpid()) + " on " + host + ", meltdemFoam, started "
      + when + "\n"
    );
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) != ssize_t(me.size()))
    {
        WarningInFunction
            << "cannot write the holder into " << lockFile << ": " << std::strerror(errno)
            << endl;
    }
}


Foam::meltdem::caseLock::~caseLock()
{
    if (fd_ < 0) return;
    // emptied, so that the next run does not report a stale holder
    if (::ftruncate(fd_, 0) != 0) {}
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
}
