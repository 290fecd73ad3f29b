/* fuzz_stl.c: the STL reader, ASCII and binary (glpgp_mesh_read on a .stl
 * file, io/mesh_io.c: welding, then glpgp_mesh_create's validation), with
 * the properties of fuzz_mesh_file.h (round trip through .obj). */
#include "fuzz_mesh_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_mesh_file(".stl", ".obj", data, size);
}
