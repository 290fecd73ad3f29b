/* fuzz_off.c: the OFF reader (glpgp_mesh_read on a .off file, io/mesh_read3d.c,
 * then the planar or surface validation), with the properties of
 * fuzz_mesh_file.h (round trip through .obj). */
#include "fuzz_mesh_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_mesh_file(".off", ".obj", data, size);
}
