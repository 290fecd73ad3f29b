/* io/output_set.c: the one atomic writer of the library (glpgp/io.h): output
 * sets (several files written under temporary names, committed together or
 * not at all, with hard-link backups of the replaced files), the
 * single-file glpgp_atomic_* on top of it, the process-wide list of live
 * temporaries for signal handlers, and the early output-path check.
 *
 * A file of a set goes through the states
 *   TEMP     the temporary exists, the destination is untouched;
 *   LINKED   + a hard link "backup" to the old destination exists;
 *   MOVED    the old destination was renamed to the backup (file systems
 *            without hard links), the destination is absent;
 *   RENAMED  the destination holds the new content (old one in the backup,
 *            if there was one);
 * and undo_file() returns any of them to "destination as before the set,
 * no temporary, no backup". Commit = close all, back up all, rename all in
 * order; a failure at any step undoes every file. */
#define _GNU_SOURCE /* fopencookie: a write error keeps its errno */
#include "glpgp/io.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

enum { ST_NONE = 0, ST_TEMP, ST_LINKED, ST_MOVED, ST_RENAMED, ST_DONE };

typedef struct out_file {
    char *dest;   /* destination */
    char *tmp;    /* temporary "STEM.tmp.PID.N.EXT" */
    char *backup; /* backup name "STEM.tmp.PID.N.old" */
    volatile sig_atomic_t state;
    int fd;          /* -1 once closed */
    FILE *f;         /* NULL for reserved files and once closed */
    int reserved;    /* written by an external writer through tmp */
    int err;         /* first errno of a write / sync / close */
    const char *err_what;
    int slot;        /* index in the process registry, -1 if none */
} out_file;

struct glpgp_output_set {
    out_file **files;
    size_t n, cap;
    int committed;
    int prepared;    /* glpgp_output_set_prepare done: the temporaries are complete */
};

/* ---- process-wide registry of live files (read by signal handlers) ------ */

static _Atomic(out_file *) g_registry[GLPGP_IO_MAX_OPEN];
static atomic_uint g_counter;

static int registry_add(out_file *of)
{
    for (int i = 0; i < GLPGP_IO_MAX_OPEN; i++) {
        out_file *expected = NULL;
        if (atomic_compare_exchange_strong(&g_registry[i], &expected, of)) return i;
    }
    return -1;
}

static void registry_remove(out_file *of)
{
    if (of->slot >= 0) atomic_store(&g_registry[of->slot], NULL);
    of->slot = -1;
}

/* Return the file system to its state before the set; async-signal-safe
 * (unlink and rename only). Returns 0, or the errno of a failed restore. */
static int undo_file(out_file *of)
{
    int err = 0;
    switch (of->state) {
    case ST_TEMP:
        unlink(of->tmp);
        break;
    case ST_LINKED:
        unlink(of->tmp);
        unlink(of->backup);
        break;
    case ST_MOVED:
        if (rename(of->backup, of->dest) != 0) err = errno;
        unlink(of->tmp);
        break;
    case ST_RENAMED:
        if (of->backup[0]) { /* backup made: restore the old destination */
            if (rename(of->backup, of->dest) != 0) err = errno;
        } else {
            unlink(of->dest); /* did not exist before */
        }
        break;
    default:
        break;
    }
    if (!err) of->state = ST_NONE;
    return err;
}

void glpgp_output_signal_cleanup(void)
{
    for (int i = 0; i < GLPGP_IO_MAX_OPEN; i++) {
        out_file *of = atomic_load(&g_registry[i]);
        if (of) undo_file(of);
    }
}

/* ---- streams that keep the errno of a failed write ----------------------- */

#if defined(__GLIBC__)
static ssize_t ck_write(void *c, const char *buf, size_t n)
{
    out_file *of = c;
    size_t done = 0;
    if (of->err) return 0;
    while (done < n) {
        ssize_t k = write(of->fd, buf + done, n - done);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) {
            of->err = k < 0 ? errno : EIO;
            of->err_what = "write";
            break;
        }
        done += (size_t)k;
    }
    return (ssize_t)done;
}

static int ck_seek(void *c, off64_t *pos, int whence)
{
    out_file *of = c;
    off_t r = lseek(of->fd, (off_t)*pos, whence);
    if (r < 0) return -1;
    *pos = r;
    return 0;
}

static int ck_close(void *c)
{
    (void)c; /* the fd is closed by close_file, which checks the result */
    return 0;
}

static FILE *open_stream(out_file *of)
{
    cookie_io_functions_t io = {NULL, ck_write, ck_seek, ck_close};
    return fopencookie(of, "w", io);
}
#else
static FILE *open_stream(out_file *of)
{
    int fd2 = dup(of->fd);
    if (fd2 < 0) return NULL;
    FILE *f = fdopen(fd2, "wb");
    if (!f) close(fd2);
    return f;
}
#endif

static void note_err(out_file *of, const char *what, int e)
{
    if (!of->err) {
        of->err = e ? e : EIO;
        of->err_what = what;
    }
}

/* Flush, fsync and close; errors are kept in of->err. */
static void close_file(out_file *of, int sync)
{
    if (of->f) {
        errno = 0;
        if (fflush(of->f) != 0) note_err(of, "write", errno);
        if (ferror(of->f)) note_err(of, "write", errno);
        if (fclose(of->f) != 0) note_err(of, "close", errno);
        of->f = NULL;
    }
    if (of->fd >= 0) {
        if (sync && !of->err && fsync(of->fd) != 0 && errno != EINVAL && errno != EROFS)
            note_err(of, "sync", errno);
        if (close(of->fd) != 0) note_err(of, "close", errno);
        of->fd = -1;
    }
}

static void free_file(out_file *of)
{
    if (!of) return;
    free(of->dest);
    free(of->tmp);
    free(of->backup);
    free(of);
}

/* ---- names --------------------------------------------------------------- */

/* Length of path without its extension (the last '.' of the last component,
 * not a leading one). */
static size_t stem_length(const char *path)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return strlen(path);
    return (size_t)(dot - path);
}

/* tmp = STEM.tmp.PID.N.EXT, backup = STEM.tmp.PID.N.old */
static glpgp_status make_names(out_file *of, unsigned n)
{
    size_t stem = stem_length(of->dest), len = strlen(of->dest) + 64;
    free(of->tmp);
    free(of->backup);
    of->tmp = malloc(len);
    of->backup = malloc(len);
    if (!of->tmp || !of->backup) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory");
    snprintf(of->tmp, len, "%.*s.tmp.%ld.%u%s", (int)stem, of->dest, (long)getpid(), n,
             of->dest + stem);
    snprintf(of->backup, len, "%.*s.tmp.%ld.%u.old", (int)stem, of->dest, (long)getpid(), n);
    return GLPGP_OK;
}

/* ---- the set ------------------------------------------------------------- */

glpgp_status glpgp_output_set_create(glpgp_output_set **out)
{
    GLPGP_CHECK(glpgp_calloc(1, sizeof **out, out));
    return GLPGP_OK;
}

static glpgp_status add_file(glpgp_output_set *s, const char *path, int reserved, out_file **res)
{
    glpgp_status st = GLPGP_OK;
    out_file *of = NULL;
    *res = NULL;
    if (!s) return GLPGP_FAIL(GLPGP_ERR_ARG, "no output set");
    if (!path || !*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "empty output path");
    if (s->committed || s->prepared) return GLPGP_FAIL(GLPGP_ERR_ARG, "output set already committed or prepared");
    for (size_t i = 0; i < s->n; i++)
        if (!strcmp(s->files[i]->dest, path))
            return GLPGP_FAIL(GLPGP_ERR_ARG, "'%s' is named twice among the outputs", path);
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", path);
    GLPGP_CHECK(glpgp_grow(&s->files, &s->cap, s->n + 1, sizeof *s->files));
    GLPGP_CHECK(glpgp_calloc(1, sizeof *of, &of));
    of->fd = -1;
    of->slot = -1;
    of->reserved = reserved;
    size_t len = strlen(path) + 1;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(len, 1, &of->dest), fail);
    memcpy(of->dest, path, len);

    int err = 0;
    for (int attempt = 0; attempt < 100; attempt++) {
        GLPGP_CHECK_GOTO(st, make_names(of, atomic_fetch_add(&g_counter, 1)), fail);
        of->fd = open(of->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (of->fd >= 0) break;
        err = errno;
        if (err != EEXIST) break;
    }
    if (of->fd < 0) {
        st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot create output file '%s': %s", path,
                        strerror(err ? err : EEXIST));
        goto fail;
    }
    of->state = ST_TEMP;
    of->slot = registry_add(of);
    if (of->slot < 0) {
        st = GLPGP_FAIL(GLPGP_ERR_LIMIT, "cannot write '%s': more than %d output files open", path,
                        GLPGP_IO_MAX_OPEN);
        goto fail;
    }
    if (reserved) {
        if (close(of->fd) != 0) note_err(of, "close", errno);
        of->fd = -1;
    } else {
        of->f = open_stream(of);
        if (!of->f) {
            st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': %s", path, strerror(errno ? errno : EIO));
            goto fail;
        }
        setvbuf(of->f, NULL, _IOFBF, 1 << 20);
    }
    s->files[s->n++] = of;
    *res = of;
    return GLPGP_OK;
fail:
    if (of) {
        if (of->f) fclose(of->f);
        if (of->fd >= 0) close(of->fd);
        undo_file(of);
        registry_remove(of);
        free_file(of);
    }
    return st;
}

glpgp_status glpgp_output_set_open(glpgp_output_set *s, const char *path, FILE **f)
{
    out_file *of;
    *f = NULL;
    GLPGP_CHECK(add_file(s, path, 0, &of));
    *f = of->f;
    return GLPGP_OK;
}

glpgp_status glpgp_output_set_reserve(glpgp_output_set *s, const char *path, const char **tmp_path)
{
    out_file *of;
    *tmp_path = NULL;
    GLPGP_CHECK(add_file(s, path, 1, &of));
    *tmp_path = of->tmp;
    return GLPGP_OK;
}

/* Undo every file (in reverse order); a restore that fails is appended to
 * the current error. */
static void undo_all(glpgp_output_set *s)
{
    for (size_t i = s->n; i-- > 0;) {
        out_file *of = s->files[i];
        if (of->f || of->fd >= 0) close_file(of, 0);
        int e = undo_file(of);
        if (e) {
            glpgp_log(GLPGP_LOG_WARNING, "could not restore '%s' (%s); its old content is in '%s'",
                      of->dest, strerror(e), of->backup);
        }
        registry_remove(of);
    }
}

/* Step 1 of a commit: every temporary complete on disk (see below). */
static glpgp_status complete_temps(glpgp_output_set *s)
{
    struct stat sb;
    /* 1. every temporary complete on disk: flush, keep the mode of a replaced
     *    regular file, fsync, close */
    for (size_t i = 0; i < s->n; i++) {
        out_file *of = s->files[i];
        if (of->reserved) {
            if (lstat(of->tmp, &sb) != 0 || !S_ISREG(sb.st_mode)) note_err(of, "write", errno ? errno : ENOENT);
            continue;
        }
        if (of->fd >= 0 && stat(of->dest, &sb) == 0 && S_ISREG(sb.st_mode)) {
            if (of->f) fflush(of->f);
            fchmod(of->fd, sb.st_mode & 07777);
        }
        close_file(of, 1);
    }
    for (size_t i = 0; i < s->n; i++) {
        out_file *of = s->files[i];
        if (of->err) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': %s", of->dest, strerror(of->err));
    }
    return GLPGP_OK;
}

glpgp_status glpgp_output_set_prepare(glpgp_output_set *s)
{
    if (!s) return GLPGP_FAIL(GLPGP_ERR_ARG, "no output set");
    if (s->committed || s->prepared) return GLPGP_FAIL(GLPGP_ERR_ARG, "output set already prepared or committed");
    s->prepared = 1;
    glpgp_status st = complete_temps(s);
    if (st != GLPGP_OK) {
        s->committed = 1; /* nothing more to do with it */
        undo_all(s);
    }
    return st;
}

glpgp_status glpgp_output_set_commit(glpgp_output_set *s)
{
    if (!s) return GLPGP_FAIL(GLPGP_ERR_ARG, "no output set");
    if (s->committed) return GLPGP_FAIL(GLPGP_ERR_ARG, "output set already committed");
    s->committed = 1;
    glpgp_status st = GLPGP_OK;
    struct stat sb;
    if (!s->prepared) GLPGP_CHECK_GOTO(st, complete_temps(s), fail);

    /* 2. hard-link backups of the destinations that exist */
    for (size_t i = 0; i < s->n; i++) {
        out_file *of = s->files[i];
        if (lstat(of->dest, &sb) != 0) {
            if (errno != ENOENT) {
                st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': %s", of->dest, strerror(errno));
                goto fail;
            }
            of->backup[0] = '\0'; /* nothing to restore: undo removes the new file */
            continue;
        }
        if (S_ISDIR(sb.st_mode)) {
            st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", of->dest);
            goto fail;
        }
        if (link(of->dest, of->backup) == 0) of->state = ST_LINKED;
        /* else: no hard links here; the old file is moved aside in step 3 */
    }

    /* 3. replace, in order */
    for (size_t i = 0; i < s->n; i++) {
        out_file *of = s->files[i];
        if (of->state == ST_TEMP && of->backup[0]) {
            if (rename(of->dest, of->backup) != 0) {
                st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot replace '%s': %s", of->dest, strerror(errno));
                goto fail;
            }
            of->state = ST_MOVED;
        }
        if (rename(of->tmp, of->dest) != 0) {
            st = GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': %s", of->dest, strerror(errno));
            goto fail;
        }
        of->state = ST_RENAMED;
    }

    /* 4. done: drop the backups */
    for (size_t i = 0; i < s->n; i++) {
        out_file *of = s->files[i];
        registry_remove(of);
        if (of->backup[0]) unlink(of->backup);
        of->state = ST_DONE;
    }
    return GLPGP_OK;
fail:
    undo_all(s);
    return st;
}

void glpgp_output_set_destroy(glpgp_output_set **sp)
{
    if (!sp || !*sp) return;
    glpgp_output_set *s = *sp;
    undo_all(s);
    for (size_t i = 0; i < s->n; i++) free_file(s->files[i]);
    free(s->files);
    free(s);
    *sp = NULL;
}

/* ---- one atomic file ------------------------------------------------------ */

glpgp_status glpgp_atomic_open(glpgp_atomic_file *af, const char *path)
{
    memset(af, 0, sizeof *af);
    glpgp_status st = GLPGP_OK;
    GLPGP_CHECK(glpgp_output_set_create(&af->set));
    GLPGP_CHECK_GOTO(st, glpgp_output_set_open(af->set, path, &af->f), fail);
    af->path = af->set->files[0]->dest;
    af->tmp = af->set->files[0]->tmp;
    return GLPGP_OK;
fail:
    glpgp_output_set_destroy(&af->set);
    memset(af, 0, sizeof *af);
    return st;
}

glpgp_status glpgp_atomic_commit(glpgp_atomic_file *af)
{
    if (!af->set) return GLPGP_FAIL(GLPGP_ERR_ARG, "commit of an output file that is not open");
    glpgp_status st = glpgp_output_set_commit(af->set);
    glpgp_output_set_destroy(&af->set);
    memset(af, 0, sizeof *af);
    if (st != GLPGP_OK) glpgp_error_push_trace(__FILE__, __LINE__);
    return st;
}

void glpgp_atomic_abort(glpgp_atomic_file *af)
{
    glpgp_output_set_destroy(&af->set);
    memset(af, 0, sizeof *af);
}

/* ---- early check ------------------------------------------------------------ */

glpgp_status glpgp_output_path_check(const char *path)
{
    char dir[4096];
    if (!path || !*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "empty output path");
    const char *slash = strrchr(path, '/');
    if (!slash) {
        strcpy(dir, ".");
    } else if (slash == path) {
        strcpy(dir, "/");
    } else {
        size_t n = (size_t)(slash - path);
        if (n >= sizeof dir) return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': path too long", path);
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' does not exist", path, dir);
    if (access(dir, W_OK | X_OK) != 0)
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': directory '%s' is not writable", path, dir);
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write '%s': it is a directory", path);
    return GLPGP_OK;
}
