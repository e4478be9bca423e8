"""One run per case folder: `meltdem run` holds an advisory lock (flock) on CASE/.meltdem.lock for
the whole run, the solver it starts included (foam-src/meltdemFoam/caseLock.H takes the same lock
when started by hand, and leaves it to `meltdem run`, which names the lock file in
MELTDEM_CASE_LOCK). The file names the holder; the kernel releases the lock when the holder dies,
so a killed run's lock is taken over, and said so."""
import fcntl
import os
import socket
import sys
import time

LOCK_FILE = ".meltdem.lock"
ENV = "MELTDEM_CASE_LOCK"


class CaseLocked(Exception):
    pass


class CaseLock:
    def __init__(self, case, what):
        self.path = os.path.join(os.path.abspath(case), LOCK_FILE)
        self.what = what
        self.fd = None
        self.stale = ""

    def acquire(self):
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = _read(fd)
            os.close(fd)
            raise CaseLocked(f"another run is using the case {os.path.dirname(self.path)} "
                             f"({holder or 'holder unknown'}): one run per case folder. Wait for it to end "
                             f"or stop it; copy the case to run it twice")
        self.stale = _read(fd)
        me = (f"pid {os.getpid()} on {socket.gethostname()}, {self.what}, started "
              f"{time.strftime('%Y-%m-%dT%H:%M:%S')}\n").encode()
        os.ftruncate(fd, 0)
        os.pwrite(fd, me, 0)
        self.fd = fd
        os.environ[ENV] = self.path
        return self

    def refresh(self):
        """Lock the case's lock file again when the folder was rebuilt (a scene's build removes
        and recreates it): the held lock is on the removed file."""
        try:
            same = os.path.samestat(os.fstat(self.fd), os.stat(self.path))
        except OSError:
            same = False
        if same:
            return self
        old = self.fd
        self.fd = None
        try:
            self.acquire()
        finally:
            os.close(old)
        return self

    def release(self):
        if self.fd is None:
            return
        try:
            os.ftruncate(self.fd, 0)
        except OSError:
            pass
        fcntl.flock(self.fd, fcntl.LOCK_UN)
        os.close(self.fd)
        self.fd = None
        if os.environ.get(ENV) == self.path:
            del os.environ[ENV]

    def __enter__(self):
        return self.acquire()

    def __exit__(self, *exc):
        self.release()


# the processes of a run: the solvers and MPI's launchers
SOLVER_PROCESSES = ("meltdem-lmp", "meltdemFoam", "mpirun", "mpiexec", "orterun", "orted", "prted", "prterun")


def solvers_in(case):
    """(pid, name) of solver processes other than this one whose working folder is the case: the
    ranks of a killed run live on for a moment (killing mpirun's group leaves them), and write."""
    case = os.path.realpath(case)
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            name = os.path.basename(os.readlink(f"/proc/{pid}/exe"))
            if name in SOLVER_PROCESSES and os.path.realpath(os.readlink(f"/proc/{pid}/cwd")) == case:
                found.append((int(pid), name))
        except OSError:
            continue
    return found


def wait_for_solvers(case, timeout=30.0, poll=0.2):
    """Wait until no solver process of an earlier run works in the case; CaseLocked naming them
    if some still do after timeout seconds. Returns the (pid, name) waited for."""
    first = solvers_in(case)
    left, end = first, time.time() + timeout
    while left and time.time() < end:
        time.sleep(poll)
        left = solvers_in(case)
    if left:
        raise CaseLocked(f"processes of an earlier run still work in the case {case} after {timeout:g} s ("
                         + ", ".join(f"pid {p} {n}" for p, n in left) + "): stop them, then run again")
    return first


def _read(fd):
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        return os.read(fd, 4096).decode(errors="replace").strip()
    except OSError:
        return ""


if __name__ == "__main__":   # hold the lock of a case for N seconds (tests)
    with CaseLock(sys.argv[1], "caselock test holder"):
        time.sleep(float(sys.argv[2]))
