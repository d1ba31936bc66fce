/* Bounded reading of text input (see input.h). The caps are checked byte by byte as the line
 * grows, so no input, however long its lines or however much of it there is, makes the reader
 * allocate more than line_max bytes or read more than total_max. */
#include "core/input.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"
#include "whirl/common.h"

/* The stop request is polled every this many bytes (a few ms of reading). */
#define INPUT_POLL_BYTES (1u << 20)

static const char *file_kind(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}

int whirl_input_open(const char *path, FILE **fp)
{
    *fp = NULL;
    if (path == NULL || path[0] == '\0') return whirl_fail(GSL_EINVAL, "empty file name");
    /* O_NONBLOCK: opening a FIFO with no writer would wait for one */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) return whirl_fail(GSL_EFAILED, "%s: cannot read: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int err = errno;
        close(fd);
        return whirl_fail(GSL_EFAILED, "%s: cannot read: %s", path, strerror(err));
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return whirl_fail(GSL_EINVAL, "%s: cannot read: %s, not a regular file", path,
                          file_kind(st.st_mode));
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    *fp = fdopen(fd, "r");
    if (*fp == NULL) {
        int err = errno;
        close(fd);
        return whirl_fail(err == ENOMEM ? GSL_ENOMEM : GSL_EFAILED, "%s: cannot read: %s",
                          path, strerror(err));
    }
    return GSL_SUCCESS;
}

whirl_line_reader whirl_line_reader_init(FILE *fp, const char *name, size_t line_max,
                                         size_t total_max)
{
    whirl_line_reader r;
    memset(&r, 0, sizeof r);
    r.fp = fp;
    r.name = name;
    r.line_max = line_max < 2 ? 2 : line_max;
    r.total_max = total_max;
    return r;
}

const char *whirl_bytes_words(char *buf, size_t size, double bytes)
{
    static const char *const unit[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int k = 0;
    while (bytes >= 1024 && k < 6) bytes /= 1024, k++;
    snprintf(buf, size, k ? "%.3g %s" : "%.0f %s", bytes, unit[k]);
    return buf;
}

int whirl_line_read(whirl_line_reader *r)
{
    char lim[32];
    if (r->status != GSL_SUCCESS) return -1;
    r->len = 0;
    r->lineno++;
    flockfile(r->fp);
    int result = 0;
    for (;;) {
        if (r->total % INPUT_POLL_BYTES == INPUT_POLL_BYTES - 1 && whirl_stop_requested()) {
            r->status = whirl_fail(WHIRL_EINTERRUPTED, "%s:%ld: interrupted while reading",
                                   r->name, r->lineno);
            break;
        }
        errno = 0;
        const int c = getc_unlocked(r->fp);
        if (c == EOF) {
            const int err = errno;
            if (ferror(r->fp))
                r->status = whirl_fail(err == ENOMEM ? GSL_ENOMEM : GSL_EFAILED,
                                       "%s:%ld: cannot read: %s", r->name, r->lineno,
                                       err ? strerror(err) : "read error");
            else result = r->len > 0; /* a last line without its newline */
            break;
        }
        if (r->total >= r->total_max) {
            r->status = whirl_fail(GSL_EINVAL, "%s:%ld: more than %s of input (the most read)",
                                   r->name, r->lineno,
                                   whirl_bytes_words(lim, sizeof lim, (double)r->total_max));
            break;
        }
        r->total++;
        if (r->len + 1 > r->line_max) {
            r->status = whirl_fail(GSL_EINVAL, "%s:%ld: line longer than %s (the longest read)",
                                   r->name, r->lineno,
                                   whirl_bytes_words(lim, sizeof lim, (double)r->line_max));
            break;
        }
        if (r->len + 2 > r->cap) { /* room for c and the NUL */
            size_t cap = r->cap ? 2 * r->cap : 256;
            if (cap > r->line_max + 1) cap = r->line_max + 1;
            char *line = realloc(r->line, cap);
            if (line == NULL) {
                r->status = whirl_fail(GSL_ENOMEM, "%s:%ld: out of memory reading a line of %s",
                                       r->name, r->lineno,
                                       whirl_bytes_words(lim, sizeof lim, (double)cap));
                break;
            }
            r->line = line;
            r->cap = cap;
        }
        r->line[r->len++] = (char)c;
        if (c == '\n') {
            result = 1;
            break;
        }
    }
    funlockfile(r->fp);
    if (r->line) r->line[r->len] = '\0';
    if (r->status != GSL_SUCCESS) return -1;
    if (result == 0) r->lineno--;
    return result;
}

void whirl_line_reader_free(whirl_line_reader *r)
{
    free(r->line);
    r->line = NULL;
    r->cap = r->len = 0;
}
