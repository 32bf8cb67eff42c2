/* failing_io.c: an LD_PRELOAD shim for tests/test_cli_hostile.sh that makes
   the file system misbehave the way a full or failing disk does, without
   needing one. Only descriptors above 2 are touched (stdout and stderr
   work as usual).

     FAILING_IO_WRITE_LIMIT=N   writes fail with ENOSPC once N bytes in all
                                have been written (a disk that fills up)
     FAILING_IO_FSYNC=eio       fsync fails with EIO (a device that fails)
     FAILING_IO_FSYNC=sleep     fsync waits 3 seconds first (to interrupt a
                                run while its temporaries exist)
     FAILING_IO_RENAME=END      the first rename to a path ending in END
                                fails with EIO (a move into place that fails
                                after others succeeded)

   Build: cc -shared -fPIC -o failing_io.so failing_io.c -ldl */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static unsigned long long written; /* a test shim: one process, one counter */

ssize_t write(int fd, const void *buffer, size_t count)
{
    static ssize_t (*real)(int, const void *, size_t);
    const char *limit = getenv("FAILING_IO_WRITE_LIMIT");
    if (real == NULL)
        real = (ssize_t(*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
    if (fd > 2 && limit != NULL) {
        unsigned long long most = strtoull(limit, NULL, 10), done = __atomic_fetch_add(&written, count, __ATOMIC_SEQ_CST);
        if (done >= most) {
            errno = ENOSPC;
            return -1;
        }
        if (done + count > most)
            count = (size_t)(most - done); /* a short write, then ENOSPC */
    }
    return real(fd, buffer, count);
}

int fsync(int fd)
{
    static int (*real)(int);
    const char *mode = getenv("FAILING_IO_FSYNC");
    if (real == NULL)
        real = (int (*)(int))dlsym(RTLD_NEXT, "fsync");
    if (fd > 2 && mode != NULL && strcmp(mode, "eio") == 0) {
        errno = EIO;
        return -1;
    }
    if (fd > 2 && mode != NULL && strcmp(mode, "sleep") == 0)
        sleep(3);
    return real(fd);
}

int rename(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    static int failed; /* once: putting files back must work */
    const char *end = getenv("FAILING_IO_RENAME");
    size_t n = end != NULL ? strlen(end) : 0, length = strlen(to);
    if (real == NULL)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    if (end != NULL && length >= n && strcmp(to + length - n, end) == 0 && !__atomic_exchange_n(&failed, 1, __ATOMIC_SEQ_CST)) {
        errno = EIO;
        return -1;
    }
    return real(from, to);
}
