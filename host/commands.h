/* commands.h: CLI subcommands implemented outside main.c. Each takes the
 * subcommand's own argv (argv[0] = subcommand name) and returns the process
 * exit code (0 ok, 1 failure, 2 usage error). */
#ifndef GLPGP_COMMANDS_H
#define GLPGP_COMMANDS_H

/* `glpgp devices`: list OpenCL platforms and devices. */
int glpgp_cmd_devices(int argc, char **argv);
/* `glpgp crosscheck INPUT [--size H] ...`: compare every stage of the OpenCL
 * path with the reference path on a mesh, print a table, exit 1 on failure. */
int glpgp_cmd_crosscheck(int argc, char **argv);

#endif
