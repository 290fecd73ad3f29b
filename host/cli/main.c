/* cli/main.c: the `glpgp` command-line tool: dispatch to the commands
 * (commands.h), the overview help and the version. Exit codes: 0 success,
 * 1 failure (one "glpgp: error: ..." line on stderr; the trace with
 * --verbose), 2 usage error (bad/unknown option or value). */
#include "cli.h"
#include "commands.h"

#include "glpgp/backends.h"
#include "glpgp/image.h"
#include "glpgp/io.h"
#include "glpgp/version.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct command {
    const char *name;
    int (*fn)(int argc, char **argv);
    const char *args, *summary;
} command;

static const command k_commands[] = {
    {"solve", glpgp_cmd_solve, "INPUT [options]",
     "compute z_u, z_v on a mesh (.obj/.msh), a built-in domain\n"
     "shape:NAME[:N] or a mask image; write .vtk/.obj, .json, quads, pictures"},
    {"generate", glpgp_cmd_generate, "SHAPE -o FILE", "write a built-in domain as .obj or .msh"},
    {"extract", glpgp_cmd_extract, "RESULT.vtk --quads OUT", "quad mesh and its quality report from a result"},
    {"quality", glpgp_cmd_quality, "MESH.msh [--size H]", "quality report of a quad mesh made elsewhere"},
    {"render", glpgp_cmd_render, "RESULT.vtk -o OUT.png", "picture of a result (grid texture, ...)"},
    {"figure", glpgp_cmd_figure, "INPUT -o OUT.png", "naive PGP and GL-PGP side by side"},
    {"mesh", glpgp_cmd_mesh, "IN -o DOMAIN.msh", "triangle mesh of a mask image, .poly or mesh (Gmsh)"},
    {"devices", glpgp_cmd_devices, "", "list OpenCL platforms and devices"},
    {"crosscheck", glpgp_cmd_crosscheck, "INPUT [options]", "compare the OpenCL and reference paths stage by stage"},
    {NULL, NULL, NULL, NULL}};

static void usage_main(FILE *f)
{
    fprintf(f,
            "glpgp %s - quad-mesh parametrization of planar domains with the\n"
            "Ginzburg-Landau periodic global parametrization (GL-PGP).\n"
            "\n"
            "Usage: glpgp <command> [arguments]\n"
            "\n"
            "Commands:\n",
            GLPGP_VERSION);
    for (const command *c = k_commands; c->name; c++) {
        char left[64];
        snprintf(left, sizeof left, "%s %s", c->name, c->args);
        fprintf(f, "  %-34s", left);
        for (const char *s = c->summary; *s; s++) {
            fputc(*s, f);
            if (*s == '\n') fprintf(f, "  %-34s", "");
        }
        fputc('\n', f);
    }
    fprintf(f, "  %-34s%s\n", "help [COMMAND]", "show this overview or a command's options");
    fprintf(f, "\nOptions: --help (this text), --version.\n"
               "Run 'glpgp <command> --help' for the options of a command.\n"
               "Exit codes: 0 success, 1 failure, 2 usage error.\n");
}

static const command *find(const char *name)
{
    for (const command *c = k_commands; c->name; c++)
        if (!strcmp(c->name, name)) return c;
    return NULL;
}

/* SIGINT / SIGTERM: remove the temporary outputs of the run (async-signal-
 * safe: unlink/rename only), say so in one line, exit 130 / 143. After a
 * failure was reported (glpgp_cli_reported: e.g. rank 0 of a failed MPI run,
 * which mpirun may end once another rank has exited) it exits with that
 * failure's code and no second line. */
static void on_signal(int sig)
{
    glpgp_output_signal_cleanup();
    const int reported = glpgp_cli_reported_code();
    if (reported) _exit(reported);
    static const char msg_int[] = "glpgp: interrupted (SIGINT): no output written\n";
    static const char msg_term[] = "glpgp: terminated (SIGTERM): no output written\n";
    if (sig == SIGINT)
        (void)!write(2, msg_int, sizeof msg_int - 1);
    else
        (void)!write(2, msg_term, sizeof msg_term - 1);
    _exit(128 + sig);
}

static void install_signal_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

/* glibc (>= 2.35) puts malloc's large blocks on transparent huge pages when
 * GLIBC_TUNABLES asks (glibc.malloc.hugetlb=1): besides the library's own
 * arrays (advised in glpgp_malloc) that covers the OpenCL runtime's buffers
 * (PoCL's host memory), whose 4 KiB first touches cost seconds at millions of
 * vertices (bench/results/gpu_h200_92301fc). The tunable is read at start,
 * so the command runs itself again once with it, unless the user set
 * GLIBC_TUNABLES or GLPGP_HUGEPAGES=0, or it runs under valgrind; a failed
 * exec goes on as it is. */
static void reexec_with_huge_pages(char **argv)
{
#if defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
    const char *opt = getenv("GLPGP_HUGEPAGES"), *pre = getenv("LD_PRELOAD");
    if ((opt && !strcmp(opt, "0")) || getenv("GLIBC_TUNABLES")) return;
    if (pre && strstr(pre, "vgpreload")) return; /* under valgrind: its own malloc, and no exec of itself */
    if (setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1) != 0) return;
    execv("/proc/self/exe", argv);
    unsetenv("GLIBC_TUNABLES");
#else
    (void)argv;
#endif
}

int main(int argc, char **argv)
{
    reexec_with_huge_pages(argv);
    glpgp_cli_set_verbosity(1);
    install_signal_handlers();
    if (argc < 2) {
        usage_main(stderr);
        return GLPGP_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
        usage_main(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        printf("glpgp %s (OpenCL backend: %s; OpenImageIO: %s; Gmsh: %s; PETSc: %s)\n", GLPGP_VERSION,
               glpgp_have_opencl() ? "built in" : "not built", glpgp_have_oiio() ? "yes" : "no",
               glpgp_have_gmsh() ? "yes" : "no", glpgp_have_petsc() ? "yes" : "no");
        return 0;
    }
    if (!strcmp(cmd, "help")) {
        if (argc < 3) {
            usage_main(stdout);
            return 0;
        }
        const command *c = find(argv[2]);
        if (!c) return glpgp_cli_usage_error(NULL, "no help for unknown command '%s'", argv[2]);
        char *hargv[] = {argv[2], (char *)"--help", NULL};
        return c->fn(2, hargv);
    }
    const command *c = find(cmd);
    if (!c) return glpgp_cli_usage_error(NULL, "unknown command '%s'", cmd);
    return c->fn(argc - 1, argv + 1);
}
