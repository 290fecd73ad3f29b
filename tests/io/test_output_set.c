/* test_output_set.c: the atomic multi-file commit (io/output_set.c):
 *  - commit writes every file of a set, replaces old ones, keeps the mode of
 *    a replaced file, leaves no temporary or backup behind; abort (destroy
 *    without commit) leaves old files untouched and removes the temporaries;
 *  - a failure in the middle of the commit (the second file's directory
 *    moved away after it was opened, a destination that became a directory,
 *    a directory made read-only) restores the files already replaced and
 *    creates none; the error names the file and the system error;
 *  - write errors keep their errno: "File too large" under RLIMIT_FSIZE and
 *    "No space left on device" on a full tmpfs (mounted in a private mount
 *    namespace when the system allows it, else reported as skipped), not
 *    "Input/output error";
 *  - glpgp_output_signal_cleanup called from a SIGTERM handler in a child
 *    removes its temporaries; reserve() gives a temporary name keeping the
 *    extension; the same path twice and an empty path are rejected. */
#define _GNU_SOURCE /* unshare, CLONE_NEWNS */
#include "testutil.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* Whole file (static buffer, "" if missing). */
static const char *content(const char *path)
{
    static char buf[4096];
    buf[0] = '\0';
    FILE *f = fopen(path, "r");
    if (!f) return "(missing)";
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Entries of dir whose name contains ".tmp." (temporaries and backups). */
static int count_tmp(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strstr(e->d_name, ".tmp.")) n++;
    closedir(d);
    return n;
}

static void rm_rf(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "chmod -R u+w '%s' 2>/dev/null; rm -rf '%s'", dir, dir);
    if (system(cmd) != 0) fprintf(stderr, "cleanup of %s failed\n", dir);
}

static void test_commit_and_abort(void)
{
    glpgp_output_set *s = NULL;
    FILE *f;
    put_file(tu_tmp_path("a.txt"), "old a\n");
    chmod(tu_tmp_path("a.txt"), 0640);
    CHECK_OK(glpgp_output_set_create(&s));
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("a.txt"), &f));
    fputs("new a\n", f);
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("b.json"), &f));
    fputs("new b\n", f);
    const char *tmp = NULL;
    CHECK_OK(glpgp_output_set_reserve(s, tu_tmp_path("c.png"), &tmp));
    CHECK(tmp && strstr(tmp, ".tmp.") && strcmp(tmp + strlen(tmp) - 4, ".png") == 0);
    put_file(tmp, "picture\n"); /* an external writer fills the reserved name */
    CHECK(count_tmp(tu_tmp_dir) == 3);
    CHECK(strcmp(content(tu_tmp_path("a.txt")), "old a\n") == 0); /* nothing replaced before the commit */
    /* the same path twice, an empty path */
    glpgp_error_clear();
    CHECK(glpgp_output_set_open(s, tu_tmp_path("a.txt"), &f) == GLPGP_ERR_ARG);
    CHECK(glpgp_output_set_open(s, "", &f) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    CHECK_OK(glpgp_output_set_commit(s));
    CHECK(glpgp_output_set_commit(s) == GLPGP_ERR_ARG); /* once */
    glpgp_error_clear();
    glpgp_output_set_destroy(&s);
    CHECK(s == NULL);
    glpgp_output_set_destroy(&s);
    CHECK(strcmp(content(tu_tmp_path("a.txt")), "new a\n") == 0);
    CHECK(strcmp(content(tu_tmp_path("b.json")), "new b\n") == 0);
    CHECK(strcmp(content(tu_tmp_path("c.png")), "picture\n") == 0);
    struct stat sb;
    CHECK(stat(tu_tmp_path("a.txt"), &sb) == 0 && (sb.st_mode & 0777) == 0640);
    CHECK(count_tmp(tu_tmp_dir) == 0);

    /* abort: the old files stay, the temporaries go */
    CHECK_OK(glpgp_output_set_create(&s));
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("a.txt"), &f));
    fputs("half written", f);
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("new.txt"), &f));
    CHECK(count_tmp(tu_tmp_dir) == 2);
    glpgp_output_set_destroy(&s);
    CHECK(strcmp(content(tu_tmp_path("a.txt")), "new a\n") == 0);
    CHECK(access(tu_tmp_path("new.txt"), F_OK) != 0);
    CHECK(count_tmp(tu_tmp_dir) == 0);

    /* atomic file = set of one */
    glpgp_atomic_file af;
    CHECK_OK(glpgp_atomic_open(&af, tu_tmp_path("a.txt")));
    CHECK(af.f && af.tmp && strstr(af.tmp, ".tmp."));
    fputs("atomic\n", af.f);
    CHECK_OK(glpgp_atomic_commit(&af));
    CHECK(af.f == NULL && af.tmp == NULL && af.set == NULL);
    CHECK(strcmp(content(tu_tmp_path("a.txt")), "atomic\n") == 0);
    CHECK(glpgp_atomic_commit(&af) == GLPGP_ERR_ARG);
    glpgp_error_clear();
    glpgp_atomic_abort(&af);
    remove(tu_tmp_path("a.txt"));
    remove(tu_tmp_path("b.json"));
    remove(tu_tmp_path("c.png"));
}

/* Set of d1/a (exists: "old") and d2/b (new); `sabotage` runs between the
 * writes and the commit. The commit must fail naming b, a must hold "old"
 * again and b must not exist. */
static void rollback_case(const char *label, void (*sabotage)(void), void (*repair)(void), int *skipped)
{
    glpgp_output_set *s = NULL;
    FILE *f;
    mkdir(tu_tmp_path("d1"), 0755);
    mkdir(tu_tmp_path("d2"), 0755);
    put_file(tu_tmp_path("d1/a.vtk"), "old");
    CHECK_OK(glpgp_output_set_create(&s));
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("d1/a.vtk"), &f));
    fputs("new", f);
    CHECK_OK(glpgp_output_set_open(s, tu_tmp_path("d2/b.json"), &f));
    fputs("new", f);
    *skipped = 0;
    sabotage();
    glpgp_error_clear();
    glpgp_status st = glpgp_output_set_commit(s);
    if (st == GLPGP_OK && *skipped) {
        printf("%s: skipped (the sabotage had no effect here)\n", label);
    } else {
        if (st != GLPGP_ERR_IO || !strstr(glpgp_error_message(), "b.json")) {
            fprintf(stderr, "%s: expected an I/O error naming b.json, got %d: %s\n", label, (int)st,
                    glpgp_error_message());
            tu_failures++;
        } else {
            printf("%s: %s\n", label, glpgp_error_message());
        }
        CHECK(strcmp(content(tu_tmp_path("d1/a.vtk")), "old") == 0);
        CHECK(count_tmp(tu_tmp_path("d1")) == 0);
    }
    glpgp_error_clear();
    glpgp_output_set_destroy(&s);
    repair();
    rm_rf(tu_tmp_path("d1"));
    rm_rf(tu_tmp_path("d2"));
    rm_rf(tu_tmp_path("d2x"));
}

static int g_skip_flag;
static void move_d2(void)
{
    CHECK(rename(tu_tmp_path("d2"), tu_tmp_path("d2x")) == 0);
}
static void no_repair(void) {}
static void d2_dir_dest(void) { CHECK(mkdir(tu_tmp_path("d2/b.json"), 0755) == 0); }
static void d2_readonly(void)
{
    chmod(tu_tmp_path("d2"), 0555);
    /* root ignores permissions: then try the immutable attribute */
    int fd = open(tu_tmp_path("d2/probe"), O_WRONLY | O_CREAT, 0644);
    if (fd >= 0) {
        close(fd);
        unlink(tu_tmp_path("d2/probe"));
        char cmd[600];
        snprintf(cmd, sizeof cmd, "chattr +i '%s' 2>/dev/null", tu_tmp_path("d2"));
        if (system(cmd) != 0) g_skip_flag = 1;
    }
}
static void d2_repair(void)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "chattr -i '%s' 2>/dev/null", tu_tmp_path("d2"));
    if (system(cmd) != 0) { /* not immutable: nothing to undo */
    }
    chmod(tu_tmp_path("d2"), 0755);
}

static void test_rollback(void)
{
    int skipped = 0;
    rollback_case("second directory moved away", move_d2, no_repair, &skipped);
    rollback_case("second destination became a directory", d2_dir_dest, no_repair, &skipped);
    g_skip_flag = 0;
    rollback_case("second directory read-only", d2_readonly, d2_repair, &g_skip_flag);
}

/* In a child: write a set of two files where the second write fails; exit
 * 0 when the commit failed with `needle` and a file name in the message, a
 * restored first file and no temporaries; 77 when the setup is impossible here. */
static int child_write_fails(const char *dir, long big, const char *needle)
{
    char a[600], b[600];
    snprintf(a, sizeof a, "%.500s/a.json", dir);
    snprintf(b, sizeof b, "%.500s/b.vtk", dir);
    FILE *f = fopen(a, "w");
    if (!f) return 77;
    fputs("old", f);
    if (fclose(f) != 0) return 77;
    glpgp_output_set *s = NULL;
    if (glpgp_output_set_create(&s) != GLPGP_OK) return 2;
    if (glpgp_output_set_open(s, a, &f) != GLPGP_OK) return 3;
    fputs("new", f);
    if (glpgp_output_set_open(s, b, &f) != GLPGP_OK) return 4;
    for (long i = 0; i < big; i++) fputc('x', f);
    glpgp_error_clear();
    glpgp_status st = glpgp_output_set_commit(s);
    /* on a full disk the small first file may be the one that fails */
    const char *msg = glpgp_error_message();
    int ok = st == GLPGP_ERR_IO && strstr(msg, needle) && (strstr(msg, "b.vtk") || strstr(msg, "a.json"));
    fprintf(stderr, "  commit: %s\n", glpgp_error_message());
    glpgp_output_set_destroy(&s);
    f = fopen(a, "r");
    char buf[16] = {0};
    if (f) {
        if (!fgets(buf, sizeof buf, f)) buf[0] = '\0';
        fclose(f);
    }
    ok = ok && !strcmp(buf, "old") && access(b, F_OK) != 0 && count_tmp(dir) == 0;
    return ok ? 0 : 1;
}

static int run_child(int (*fn)(void))
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) _exit(fn());
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static int efbig_child(void)
{
    struct rlimit rl = {64 * 1024, 64 * 1024};
    signal(SIGXFSZ, SIG_IGN);
    if (setrlimit(RLIMIT_FSIZE, &rl) != 0) return 77;
    return child_write_fails(tu_tmp_dir, 1 << 20, "File too large");
}

static int enospc_child(void)
{
    char mnt[600];
    snprintf(mnt, sizeof mnt, "%s/small", tu_tmp_dir);
    if (unshare(CLONE_NEWNS) != 0 && unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) return 77;
    if (mount("none", "/", "none", MS_REC | MS_PRIVATE, NULL) != 0) return 77; /* type ignored */
    if (mount("glpgp_test", mnt, "tmpfs", 0, "size=64k") != 0) return 77;
    return child_write_fails(mnt, 1 << 20, "No space left on device");
}

static void test_errno_kept(void)
{
    int rc = run_child(efbig_child);
    CHECK(rc == 0 || rc == 77);
    printf("write error under RLIMIT_FSIZE: %s\n", rc == 0 ? "File too large, rolled back" : rc == 77 ? "skipped" : "FAILED");
    mkdir(tu_tmp_path("small"), 0755);
    rc = run_child(enospc_child);
    CHECK(rc == 0 || rc == 77);
    printf("full tmpfs: %s\n", rc == 0 ? "No space left on device, rolled back" : rc == 77 ? "skipped (no mount namespace)" : "FAILED");
    rmdir(tu_tmp_path("small"));
    remove(tu_tmp_path("a.json"));
}

/* SIGTERM in the middle of writing: the handler removes the temporaries. */
static void on_term(int sig)
{
    glpgp_output_signal_cleanup();
    _exit(128 + sig);
}

static int signal_child(void)
{
    signal(SIGTERM, on_term);
    glpgp_output_set *s = NULL;
    FILE *f;
    if (glpgp_output_set_create(&s) != GLPGP_OK || glpgp_output_set_open(s, tu_tmp_path("sig1.vtk"), &f) != GLPGP_OK ||
        glpgp_output_set_open(s, tu_tmp_path("sig2.json"), &f) != GLPGP_OK)
        return 2;
    fputs("partial", f);
    fflush(f);
    if (count_tmp(tu_tmp_dir) != 2) return 3;
    kill(getpid(), SIGTERM);
    return 4; /* not reached */
}

static void test_signal_cleanup(void)
{
    put_file(tu_tmp_path("sig1.vtk"), "old");
    int rc = run_child(signal_child);
    CHECK(rc == 128 + SIGTERM);
    CHECK(count_tmp(tu_tmp_dir) == 0);
    CHECK(strcmp(content(tu_tmp_path("sig1.vtk")), "old") == 0);
    CHECK(access(tu_tmp_path("sig2.json"), F_OK) != 0);
    remove(tu_tmp_path("sig1.vtk"));
}

static void test_bad_destinations(void)
{
    glpgp_output_set *s = NULL;
    FILE *f;
    CHECK_OK(glpgp_output_set_create(&s));
    mkdir(tu_tmp_path("isdir.vtk"), 0755);
    glpgp_error_clear();
    CHECK(glpgp_output_set_open(s, tu_tmp_path("isdir.vtk"), &f) == GLPGP_ERR_IO);
    CHECK(strstr(glpgp_error_message(), "directory") != NULL);
    glpgp_error_clear();
    CHECK(glpgp_output_set_open(s, tu_tmp_path("missing/x.vtk"), &f) == GLPGP_ERR_IO);
    CHECK(strstr(glpgp_error_message(), "No such file or directory") != NULL);
    glpgp_error_clear();
    CHECK_OK(glpgp_output_set_commit(s)); /* an empty set commits */
    glpgp_output_set_destroy(&s);
    rmdir(tu_tmp_path("isdir.vtk"));
    CHECK(count_tmp(tu_tmp_dir) == 0);
}

int main(void)
{
    if (!tu_tmp_init("test_oset")) return 1;
    test_commit_and_abort();
    test_rollback();
    test_errno_kept();
    test_signal_cleanup();
    test_bad_destinations();
    CHECK(count_tmp(tu_tmp_dir) == 0);
    rm_rf(tu_tmp_dir);
    TEST_DONE();
}
