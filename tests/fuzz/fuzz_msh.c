/* fuzz_msh.c: the Gmsh MSH 2.2 / 4.1 triangle-mesh reader (glpgp_mesh_read on a
 * .msh file: io/msh_read.c, io/mesh_io.c, then glpgp_mesh_create), with the
 * properties of fuzz_mesh_file.h. */
#include "fuzz_mesh_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_mesh_file(".msh", ".msh", data, size);
}
