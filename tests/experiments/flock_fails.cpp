// A flock() that fails as on a file system without locks (Lustre mounted noflock: ENOSYS),
// loaded into `deepvox` with LD_PRELOAD by test_long_runs.cpp to check that writer.lock alone
// keeps one writer per result folder there.
#include <sys/file.h>

#include <cerrno>

extern "C" int flock(int, int) {
  errno = ENOSYS;
  return -1;
}
