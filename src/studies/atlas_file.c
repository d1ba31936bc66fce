/* The atlas's file written by one run at a time (whirl/atlas.h): a lock taken on the file from
 * before it is read until the run's last row, passed to each new file before it is renamed over
 * the old one, so that no other run (the command line's or the Python package's) can take the
 * file between two of this run's rewrites.
 *
 * flock, not a POSIX record lock: the latter ends when the process closes any descriptor of the
 * file, as the reading of a resumed file through another descriptor does. */
#define _XOPEN_SOURCE 700 /* realpath, mkstemp, fchmod */
#define _DEFAULT_SOURCE   /* flock */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "whirl/atlas.h"
#include "core/error.h"

struct whirl_atlas_file {
    int fd;     /* the locked file, open for reading */
    int made;   /* this run made it (empty) and has not replaced it */
    char *path; /* as given */
};

/* The message of a lock another run holds. */
static int locked_error(const char *path)
{
    return whirl_fail(GSL_EFAILED, "'%s' is being written by another run (locked): wait for it "
                      "or write another file", path);
}

/* Opens and locks path once: 0 with *fd, or -1 to try again (the path changed between two
 * steps: another run made, removed or replaced it), or a status with a message. */
static int lock_once(const char *path, int make, int *fd, int *made)
{
    struct stat st, now;
    *made = 0;
    if (stat(path, &st) == 0) {
        if (!S_ISREG(st.st_mode))
            return whirl_fail(GSL_EINVAL, "'%s' is not a regular file (it is rewritten after "
                              "every chunk)", path);
        /* O_NONBLOCK: never wait in open() (a FIFO put there since) */
        *fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    } else if (!make)
        return whirl_fail(GSL_EINVAL, "cannot read '%s': no such regular file", path);
    else if ((*fd = open(path, O_RDWR | O_CREAT | O_EXCL | O_NOCTTY, 0666)) >= 0)
        *made = 1;
    if (*fd < 0 && errno == EEXIST) return -1;
    if (*fd < 0 && errno == ENOENT && stat(path, &st) == 0) return -1;
    if (*fd < 0) return whirl_fail(GSL_EFAILED, "cannot lock '%s': %s", path, strerror(errno));
    if (flock(*fd, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        close(*fd); /* a file made here and locked by another run first is that run's now */
        return err == EWOULDBLOCK ? locked_error(path)
                                  : whirl_fail(GSL_EFAILED, "cannot lock '%s': %s", path,
                                               strerror(err));
    }
    /* the file locked must still be the one the path names (another run may have replaced it
     * between the open and the lock) */
    if (fstat(*fd, &st) != 0 || stat(path, &now) != 0 || st.st_dev != now.st_dev ||
        st.st_ino != now.st_ino || !S_ISREG(st.st_mode)) {
        close(*fd);
        return whirl_fail(GSL_EFAILED, "'%s' was replaced by another run while this one started",
                          path);
    }
    fcntl(*fd, F_SETFL, fcntl(*fd, F_GETFL) & ~O_NONBLOCK);
    return GSL_SUCCESS;
}

whirl_atlas_file *whirl_atlas_file_alloc(const char *path, int make)
{
    if (path == NULL || *path == '\0') {
        whirl_fail(GSL_EINVAL, "the atlas's file needs a name");
        return NULL;
    }
    for (int tries = 0; tries < 8; tries++) {
        int fd, made;
        const int status = lock_once(path, make, &fd, &made);
        if (status < 0) continue;
        if (status != GSL_SUCCESS) return NULL;
        whirl_atlas_file *f = malloc(sizeof *f);
        char *copy = malloc(strlen(path) + 1);
        if (f == NULL || copy == NULL) {
            if (made) unlink(path);
            close(fd);
            free(f);
            free(copy);
            whirl_fail(GSL_ENOMEM, "out of memory");
            return NULL;
        }
        f->fd = fd;
        f->made = made;
        f->path = strcpy(copy, path);
        return f;
    }
    whirl_fail(GSL_EFAILED, "cannot lock '%s': other runs keep making and removing it", path);
    return NULL;
}

int whirl_atlas_file_fd(const whirl_atlas_file *f) { return f->fd; }

int whirl_atlas_file_made(const whirl_atlas_file *f) { return f->made; }

/* The file the path names in the end (a symlink's target), into real (PATH_MAX). */
static const char *target_of(const char *path, char *real)
{
    return realpath(path, real) ? real : path;
}

int whirl_atlas_file_replace(whirl_atlas_file *f, int fd, const char *tmp)
{
    char real[PATH_MAX];
    /* the new file is locked before it is renamed over the old one (nobody else can hold it:
     * it has no name yet but its temporary one) */
    const int mine = dup(fd);
    if (mine < 0 || flock(mine, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        if (mine >= 0) close(mine);
        return whirl_fail(GSL_EFAILED, "cannot lock '%s': %s", f->path, strerror(err));
    }
    if (rename(tmp, target_of(f->path, real)) != 0) {
        const int err = errno;
        close(mine);
        return whirl_fail(GSL_EFAILED, "cannot write '%s': %s", f->path, strerror(err));
    }
    close(f->fd); /* the old file's lock: it was replaced */
    f->fd = mine;
    f->made = 0;
    return GSL_SUCCESS;
}

int whirl_atlas_file_commit(whirl_atlas_file *f, const char *data, size_t n)
{
    char real[PATH_MAX];
    const char *target = target_of(f->path, real);
    const size_t len = strlen(target);
    char *tmp = malloc(len + sizeof ".tmp.XXXXXX");
    if (tmp == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    memcpy(tmp, target, len);
    memcpy(tmp + len, ".tmp.XXXXXX", sizeof ".tmp.XXXXXX");
    const int fd = mkstemp(tmp);
    if (fd < 0) {
        const int err = errno;
        free(tmp);
        return whirl_fail(GSL_EFAILED, "cannot write '%s': %s", f->path, strerror(err));
    }
    int err = 0;
    struct stat st;
    if (fstat(f->fd, &st) != 0 || fchmod(fd, st.st_mode & 07777) != 0) err = errno;
    for (size_t done = 0; done < n && !err;) {
        const ssize_t k = write(fd, data + done, n - done);
        if (k < 0 && errno != EINTR) err = errno;
        if (k > 0) done += (size_t)k;
    }
    if (!err && fsync(fd) != 0) err = errno;
    int status = err ? whirl_fail(GSL_EFAILED, "cannot write '%s': %s", f->path, strerror(err))
                     : whirl_atlas_file_replace(f, fd, tmp);
    if (status != GSL_SUCCESS) unlink(tmp);
    close(fd);
    free(tmp);
    return status;
}

void whirl_atlas_file_free(whirl_atlas_file *f)
{
    if (f == NULL) return;
    struct stat mine, now;
    /* the empty file made to hold the lock, when the run wrote nothing in its place */
    if (f->made && fstat(f->fd, &mine) == 0 && mine.st_size == 0 && stat(f->path, &now) == 0 &&
        mine.st_dev == now.st_dev && mine.st_ino == now.st_ino)
        unlink(f->path);
    close(f->fd);
    free(f->path);
    free(f);
}
