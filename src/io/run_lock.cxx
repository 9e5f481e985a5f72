// One run per output folder (run_lock.hpp).
//
// The lock is output_dir/.burst.lock, created with O_CREAT | O_EXCL by rank 0 (atomic on local and
// NFSv3+ file systems), holding "host <name>", "pid <pid>", "started <time>" and "program <name>". A
// second run into the folder finds it and stops before writing anything there. The lock is stale,
// and is taken over with a note, when
//   - it names this host and its pid is not alive, or runs another program than the one that wrote
//     the lock ("program", the executable's file name; /proc/<pid>/exe), or
//   - it names another host and has not been touched for -output_lock_stale_time seconds (default
//     3600; a live run touches it at least once a minute, so only a run stuck for an hour in one step
//     or a dead one qualifies), or
//   - it cannot be parsed and is older than a minute (a lock that is being written is younger).
#include "run_lock.hpp"
#include "util.hpp"
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fstream>
#include <signal.h>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <utime.h>

namespace burst {

namespace {
std::string lock_path;
bool        held          = false;
pid_t       holder_pid    = 0;
time_t      last_touch    = 0;
PetscReal   stale_seconds = 3600; // -output_lock_stale_time

std::string HostName()
{
  char name[256] = "";
  if (gethostname(name, sizeof(name) - 1) != 0) std::strcpy(name, "unknown");
  return name;
}

// The file name of a process's executable ("" if unknown: no /proc, or not ours to read).
std::string ProgramOf(const std::string &pid)
{
  char          buf[4096];
  const ssize_t n = readlink(("/proc/" + pid + "/exe").c_str(), buf, sizeof(buf) - 1);
  if (n <= 0) return "";
  std::string  exe(buf, (size_t)n);
  const size_t del = exe.find(" (deleted)"); // a rebuilt executable
  if (del != std::string::npos) exe.resize(del);
  return exe.substr(exe.find_last_of('/') + 1);
}

// Alive: the pid exists and, where /proc tells, runs the program that wrote the lock (a pid reused
// by another program after a crash does not hold the folder).
bool PidRunsProgram(long pid, const std::string &program)
{
  if (kill((pid_t)pid, 0) != 0 && errno != EPERM) return false;
  if (program.empty()) return true;
  const std::string theirs = ProgramOf(std::to_string(pid));
  if (!theirs.empty()) return theirs == program;
  std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline", std::ios::binary);
  if (!in) return true; // no /proc: trust the pid
  std::stringstream s;
  s << in.rdbuf();
  return s.str().find(program) != std::string::npos;
}

void ReleaseAtExit() { RunLockRelease(); }

// Rank 0: 0 = acquired, 1 = held by a live run (message in `why`), 2 = cannot create (message).
int TryAcquire(const std::string &path, double stale_seconds, std::string &why, std::string &note)
{
  const std::string host = HostName();
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      char         text[512];
      const time_t now = time(nullptr);
      char         when[64];
      std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
      const std::string program = ProgramOf("self");
      const int         n       = std::snprintf(text, sizeof(text), "host %s\npid %ld\nstarted %s\nprogram %s\n", host.c_str(), (long)getpid(), when, program.empty() ? "burst" : program.c_str());
      const bool        ok      = write(fd, text, (size_t)n) == n;
      close(fd);
      if (!ok) {
        unlink(path.c_str());
        why = "the folder cannot be written (permissions, a file of that name, or a full disk): the lock file " + path + " cannot be written (" + std::strerror(errno) + ")";
        return 2;
      }
      return 0;
    }
    if (errno != EEXIST) {
      why = "the folder cannot be written (permissions, a file of that name, or a full disk): the lock file " + path + " cannot be created (" + std::strerror(errno) + ")";
      return 2;
    }
    // Someone holds it: alive or stale?
    std::ifstream in(path);
    std::string   key, their_host, started, program;
    long          their_pid = -1;
    for (std::string line; std::getline(in, line);) {
      std::istringstream l(line);
      l >> key;
      if (key == "host") l >> their_host;
      else if (key == "pid") l >> their_pid;
      else if (key == "started") std::getline(l >> std::ws, started);
      else if (key == "program") l >> program;
    }
    struct stat st;
    if (stat(path.c_str(), &st) != 0) continue; // gone meanwhile: try again
    const double age = difftime(time(nullptr), st.st_mtime);
    bool         alive;
    std::string  reason;
    if (their_host.empty() || their_pid <= 0) {
      alive  = age < 60;
      reason = "it cannot be read and is " + std::to_string((long)age) + " s old";
    } else if (their_host == host) {
      alive  = PidRunsProgram(their_pid, program);
      reason = "process " + std::to_string(their_pid) + " no longer runs " + (program.empty() ? std::string("burst") : program) + " on this host";
    } else {
      alive  = age < stale_seconds;
      reason = "host " + their_host + " has not touched it for " + std::to_string((long)age) + " s (-output_lock_stale_time " + std::to_string((long)stale_seconds) + ")";
    }
    if (alive) {
      why = "it is in use by another run: host " + (their_host.empty() ? std::string("(unknown)") : their_host) + ", pid " + (their_pid > 0 ? std::to_string(their_pid) : std::string("(unknown)")) +
            (started.empty() ? std::string() : ", started " + started) + " (lock file " + path + "). Wait for that run to end or choose another -output_dir; if that run is gone, remove the lock file";
      return 1;
    }
    note += "Note: taking over the stale lock " + path + " of host " + (their_host.empty() ? std::string("(unknown)") : their_host) + ", pid " + std::to_string(their_pid) + ": " + reason + "\n";
    unlink(path.c_str()); // another run taking it over at the same moment: the O_EXCL retry decides
  }
  why = "the lock file " + path + " could not be taken over (another run keeps replacing it)";
  return 1;
}
} // namespace

PetscErrorCode RunLockSetUp(Simulation &sim)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(sim.comm, "", "Output folder lock", "Output");
  PetscCall(PetscOptionsReal("-output_lock_stale_time",
                             "Age (s) after which another host's lock on -output_dir (output_dir/.burst.lock) counts as left by a dead run and is taken over, > 0 (a lock of this host is stale as soon as its process is gone)", "", stale_seconds,
                             &stale_seconds, nullptr));
  PetscOptionsEnd();
  PetscCall(CheckRange(sim.comm, "-output_lock_stale_time", stale_seconds, 0, PETSC_MAX_REAL, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RunLockAcquire(Simulation &sim)
{
  const PetscReal stale = stale_seconds;
  PetscFunctionBeginUser;
  const std::string path = sim.output.dir + "/.burst.lock";
  std::string       why, note;
  PetscInt          status = 0;
  if (!sim.rank) {
    status = TryAcquire(path, stale, why, note);
    if (status == 0) {
      lock_path              = path;
      held                   = true;
      holder_pid             = getpid();
      last_touch             = time(nullptr);
      static bool registered = false;
      if (!registered) registered = std::atexit(ReleaseAtExit) == 0;
    }
  }
  PetscCallMPI(MPI_Bcast(&status, 1, MPIU_INT, 0, sim.comm));
  if (!note.empty()) PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s", note.c_str()));
  if (status) {
    char msg[2048] = "";
    if (!sim.rank) std::snprintf(msg, sizeof(msg), "%s", why.c_str());
    PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, sim.comm));
    SETERRQ(sim.comm, status == 1 ? PETSC_ERR_USER_INPUT : PETSC_ERR_FILE_WRITE, "Option -output_dir %s: %s", sim.output.dir.c_str(), msg);
  }
  PetscCall(PetscInfo(nullptr, "Output folder lock %s held by pid %ld\n", path.c_str(), (long)getpid()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void RunLockTouch()
{
  if (!held) return;
  const time_t now = time(nullptr);
  if (difftime(now, last_touch) < 60) return;
  last_touch = now;
  (void)utime(lock_path.c_str(), nullptr);
}

void RunLockRelease()
{
  if (!held || getpid() != holder_pid) return;
  held = false;
  (void)unlink(lock_path.c_str());
}

} // namespace burst
