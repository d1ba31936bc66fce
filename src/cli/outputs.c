/* Files and signals of the whirl program (docs/guide/files-and-signals.md):
 *   - outputs written atomically: a temporary file beside the target (beside a symlink's target,
 *     keeping the target's mode and owner), renamed into place by the commit; several outputs
 *     of one command committed all or none;
 *   - the checks made before any work: no two outputs on one file, no output on an input, no
 *     output on a read-only file, a directory or a dangling symlink, every output's folder
 *     writable;
 *   - a lock on a map file while a run writes it; the rows a resumed file keeps, checked;
 *   - the exit status after a signal. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"

int cli_exit_status(int rc)
{
    if ((rc == 1 || rc == CLI_EXIT_INTERRUPTED) && whirl_stop_requested()) {
        const int sig = whirl_stop_signal();
        return sig > 0 ? 128 + sig : CLI_EXIT_INTERRUPTED;
    }
    return rc;
}

void cli_put_escaped(FILE *fp, const char *s)
{
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c == '\n') fputs("\\n", fp);
        else if (c == '\r') fputs("\\r", fp);
        else if (c == '\t') fputs("\\t", fp);
        else if (c < 0x20 || c == 0x7f) fprintf(fp, "\\x%02x", c);
        else fputc(c, fp);
    }
}

/* ---- where a path leads ---- */

/* The folder of path ("." when it has none) into dir (size bytes); the name after it in
 * *base. */
static void split_path(const char *path, char *dir, size_t size, const char **base)
{
    const char *slash = strrchr(path, '/');
    if (slash == NULL) {
        snprintf(dir, size, ".");
        *base = path;
    } else if (slash == path) {
        snprintf(dir, size, "/");
        *base = slash + 1;
    } else {
        snprintf(dir, size, "%.*s", (int)(slash - path), path);
        *base = slash + 1;
    }
}

/* The identity of the file a path names: the file's device and inode when it exists, else its
 * folder's and its name (two paths to one file not yet written are then the same too). */
typedef struct file_id {
    int exists;       /* the file exists (stat, through symlinks) */
    int regular;      /* ... and is a regular file */
    dev_t dev;
    ino_t ino;
    const char *base; /* the name in its folder, when it does not exist */
} file_id;

static int identify(const char *path, file_id *id)
{
    struct stat st;
    memset(id, 0, sizeof *id);
    if (stat(path, &st) == 0) {
        id->exists = 1;
        id->regular = S_ISREG(st.st_mode);
        id->dev = st.st_dev, id->ino = st.st_ino;
        return 0;
    }
    char dir[PATH_MAX];
    split_path(path, dir, sizeof dir, &id->base);
    if (stat(dir, &st) != 0) return -1;
    id->dev = st.st_dev, id->ino = st.st_ino;
    return 0;
}

static int same_file(const file_id *a, const file_id *b)
{
    if (a->exists != b->exists || a->dev != b->dev || a->ino != b->ino) return 0;
    return a->exists || strcmp(a->base, b->base) == 0;
}

/* ---- the checks before the work ---- */

/* One output: writable, or 1 after an error. */
static int check_output(const cli_command *cmd, const cli_path *o)
{
    const char *path = o->path;
    if (path[0] == '\0') return cli_error(cmd, "%s: empty output file name", o->what);
    struct stat lst, st;
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode) && stat(path, &st) != 0)
        return cli_error(cmd, "%s '%s': a symbolic link to nothing (%s)", o->what, path,
                         strerror(errno));
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return cli_error(cmd, "%s '%s': a directory, not a file", o->what, path);
        if (!S_ISREG(st.st_mode)) return 0; /* a device or a FIFO, written in place */
        /* a file nobody may write is not replaced, not even by root */
        if ((st.st_mode & 0222) == 0 || access(path, W_OK) != 0)
            return cli_error(cmd, "%s '%s': the file is read-only (make it writable or remove "
                             "it first)", o->what, path);
    }
    /* the temporary file goes beside the file (a symlink's target): one is made and removed
     * now, the test that tells (access() says yes to root on a read-only file system or /proc) */
    char real[PATH_MAX], dir[PATH_MAX], probe[PATH_MAX + 32];
    const char *base;
    split_path(realpath(path, real) ? real : path, dir, sizeof dir, &base);
    snprintf(probe, sizeof probe, "%s/.whirl-probe.XXXXXX", dir);
    int fd = mkstemp(probe);
    if (fd < 0)
        return cli_error(cmd, "%s '%s': cannot write in '%s': %s", o->what, path, dir,
                         strerror(errno));
    close(fd);
    unlink(probe);
    return 0;
}

int cli_check_files(const cli_command *cmd, const cli_path *outputs, size_t n_outputs,
                    const cli_path *inputs, size_t n_inputs)
{
    file_id id[CLI_FILES_MAX];
    if (n_outputs > CLI_FILES_MAX) return cli_error(cmd, "too many output files");
    for (size_t i = 0; i < n_outputs; i++) {
        const cli_path *o = &outputs[i];
        if (o->path == NULL || strcmp(o->path, "-") == 0) {
            id[i].exists = -1; /* standard output */
            continue;
        }
        if (check_output(cmd, o)) return 1;
        if (identify(o->path, &id[i]) != 0)
            return cli_error(cmd, "%s '%s': %s", o->what, o->path, strerror(errno));
        if (id[i].exists && !id[i].regular) continue; /* /dev/null twice is fine */
        for (size_t j = 0; j < i; j++)
            if (id[j].exists >= 0 && same_file(&id[i], &id[j]))
                return cli_error(cmd, "%s '%s' and %s '%s' are the same file: one would "
                                 "replace the other", outputs[j].what, outputs[j].path, o->what,
                                 o->path);
        for (size_t j = 0; j < n_inputs; j++) {
            file_id in;
            if (inputs[j].path == NULL || strcmp(inputs[j].path, "-") == 0) continue;
            if (identify(inputs[j].path, &in) == 0 && in.exists && same_file(&id[i], &in))
                return cli_error(cmd, "%s '%s' is the input %s '%s': it would be replaced",
                                 o->what, o->path, inputs[j].what, inputs[j].path);
        }
    }
    return 0;
}

int cli_check_options_files(const cli_command *cmd, const cli_option *opts, size_t nopts,
                            const char *given, const char *const *positional, size_t npos)
{
    cli_path out[CLI_FILES_MAX], in[CLI_FILES_MAX + 1];
    size_t n_out = 0, n_in = 0;
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        if (!given[i] || o->type != CLI_STRING || o->meta == NULL || strcmp(o->meta, "FILE") != 0)
            continue;
        cli_path f = {o->name, *(const char *const *)o->value};
        if (o->input && n_in < CLI_FILES_MAX) in[n_in++] = f;
        else if (!o->input && n_out < CLI_FILES_MAX) out[n_out++] = f;
    }
    for (size_t k = 0; k < npos && n_in <= CLI_FILES_MAX; k++)
        in[n_in++] = (cli_path){"file", positional[k]};
    return cli_check_files(cmd, out, n_out, in, n_in);
}

/* ---- output written atomically ---- */

int cli_out_open(const cli_command *cmd, cli_out *out, const char *path)
{
    out->fp = stdout;
    out->path = NULL;
    out->tmp = NULL;
    out->shown = NULL;
    if (path == NULL || strcmp(path, "-") == 0) return 0;
    if (path[0] == '\0') return cli_error(cmd, "empty output file name");
    out->shown = path;
    struct stat st;
    const int exists = stat(path, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        /* A device or a FIFO is written in place (it cannot be renamed over); O_NONBLOCK: a
         * FIFO with no reader fails at once (ENXIO) instead of waiting in open() */
        int fd = open(path, O_WRONLY | O_NONBLOCK | O_NOCTTY);
        if (fd < 0 && errno == ENXIO)
            return cli_error(cmd, "cannot write '%s': a FIFO with no reader", path);
        if (fd < 0) return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
        out->fp = fdopen(fd, "w");
        if (out->fp == NULL) {
            close(fd);
            return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        }
        return 0;
    }
    /* through a symlink: the temporary file beside its target, renamed over the target */
    char real[PATH_MAX];
    const char *target = exists && realpath(path, real) ? real : path;
    size_t len = strlen(target);
    out->path = malloc(len + 1);
    out->tmp = malloc(len + 16);
    if (out->path == NULL || out->tmp == NULL) {
        cli_out_abort(out);
        return cli_error(cmd, "out of memory");
    }
    memcpy(out->path, target, len + 1);
    snprintf(out->tmp, len + 16, "%s.tmp.XXXXXX", target);
    int fd = mkstemp(out->tmp);
    if (fd < 0) {
        int err = errno;
        free(out->tmp);
        out->tmp = NULL;
        cli_out_abort(out);
        return cli_error(cmd, "cannot write '%s': %s", path, strerror(err));
    }
    /* mkstemp creates the file 0600: give it the mode and owner of the file it replaces, or
     * the mode a plain fopen would (0666 less umask) */
    if (exists) {
        if (fchmod(fd, st.st_mode & 07777) != 0 ||
            ((st.st_uid != geteuid() || st.st_gid != getegid()) &&
             fchown(fd, st.st_uid, st.st_gid) != 0)) {
            int err = errno;
            close(fd);
            cli_out_abort(out);
            return cli_error(cmd, "cannot replace '%s' keeping its mode and owner: %s", path,
                             strerror(err));
        }
    } else {
        mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask);
    }
    out->fp = fdopen(fd, "w");
    if (out->fp == NULL) {
        close(fd);
        cli_out_abort(out);
        return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
    }
    return 0;
}

/* Flushes and closes one output (standard output: flushes it). Returns 0, or errno (EIO when
 * none is known). */
static int out_close(cli_out *out)
{
    errno = 0;
    if (out->fp == stdout) {
        if (fflush(stdout) != 0 || ferror(stdout)) return errno ? errno : EIO;
        return 0;
    }
    if (out->fp == NULL) return 0;
    int bad = 0, err = 0;
    if (ferror(out->fp)) { /* a write failed: try again for its reason (EFBIG, ENOSPC, ...) */
        clearerr(out->fp);
        errno = 0;
        bad = 1;
        err = fputc('\n', out->fp) == EOF || fflush(out->fp) != 0 ? errno : 0;
    } else if (fflush(out->fp) != 0) bad = 1, err = errno;
    if (fclose(out->fp) != 0 && !bad) bad = 1, err = errno;
    out->fp = NULL;
    return bad ? (err ? err : EIO) : 0;
}

int cli_out_commit_all(const cli_command *cmd, cli_out *const *outs, size_t n)
{
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++) {
        int err = out_close(outs[i]);
        if (err)
            rc = cli_error(cmd, "cannot write %s: %s%s",
                           outs[i]->shown ? outs[i]->shown : "standard output", strerror(err),
                           n > 1 ? " (no file written)" : "");
    }
    for (size_t i = 0; i < n && rc == 0; i++)
        if (outs[i]->tmp && rename(outs[i]->tmp, outs[i]->path) != 0)
            rc = cli_error(cmd, "cannot write '%s': %s", outs[i]->shown, strerror(errno));
        else if (outs[i]->tmp) {
            free(outs[i]->tmp);
            outs[i]->tmp = NULL;
        }
    for (size_t i = 0; i < n; i++) cli_out_abort(outs[i]);
    return rc;
}

int cli_out_commit(const cli_command *cmd, cli_out *out)
{
    return cli_out_commit_all(cmd, &out, 1);
}

void cli_out_abort(cli_out *out)
{
    if (out->fp && out->fp != stdout) fclose(out->fp);
    out->fp = NULL;
    if (out->tmp) remove(out->tmp);
    free(out->tmp);
    free(out->path);
    out->tmp = out->path = NULL;
}

/* ---- maps written by one run at a time ---- */

/* The lock is the library's (whirl_atlas_file, src/studies/atlas_file.c), shared with the
 * Python package; here the cases the command line writes in place, and a stream to read the
 * locked file through. */

int cli_lock_take(const cli_command *cmd, cli_lock *l, const char *path, int make)
{
    memset(l, 0, sizeof *l);
    if (path == NULL || strcmp(path, "-") == 0) return 0;
    struct stat st;
    if (stat(path, &st) == 0 ? !S_ISREG(st.st_mode) : !make)
        return 0; /* a device, written in place; a file to resume that is not there */
    whirl_atlas_file *f = whirl_atlas_file_alloc(path, make);
    if (f == NULL) return cli_error(cmd, "%s", whirl_last_error());
    const int fd = dup(whirl_atlas_file_fd(f));
    l->fp = fd >= 0 ? fdopen(fd, "r") : NULL;
    if (l->fp == NULL) {
        if (fd >= 0) close(fd);
        whirl_atlas_file_free(f);
        return cli_error(cmd, "out of memory");
    }
    l->file = f;
    return 0;
}

int cli_lock_commit(const cli_command *cmd, cli_lock *l, cli_out *out)
{
    if (l->file == NULL || out->tmp == NULL) return cli_out_commit(cmd, out);
    /* the contents written whole (and synced) under the temporary name, then put in place by
     * the library, which locks the new file before it renames it over the old one */
    const int fd = dup(fileno(out->fp));
    int err = fd < 0 ? errno : out_close(out);
    if (err) {
        if (fd >= 0) close(fd);
        cli_out_abort(out);
        return cli_error(cmd, "cannot write %s: %s", out->shown, strerror(err));
    }
    const int status = whirl_atlas_file_replace(l->file, fd, out->tmp);
    close(fd);
    if (status != GSL_SUCCESS) {
        cli_out_abort(out);
        return cli_error(cmd, "%s", whirl_last_error());
    }
    free(out->tmp);
    out->tmp = NULL;
    cli_out_abort(out);
    /* the stream reads the new file */
    const int again = dup(whirl_atlas_file_fd(l->file));
    FILE *fp = again >= 0 ? fdopen(again, "r") : NULL;
    if (fp == NULL) {
        if (again >= 0) close(again);
        return cli_error(cmd, "out of memory");
    }
    fclose(l->fp);
    l->fp = fp;
    return 0;
}

void cli_lock_release(cli_lock *l)
{
    if (l->fp) fclose(l->fp);
    whirl_atlas_file_free(l->file);
    memset(l, 0, sizeof *l);
}
