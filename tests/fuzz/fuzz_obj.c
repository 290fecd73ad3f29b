/* fuzz_obj.c: the OBJ triangle-mesh reader (glpgp_mesh_read on a .obj file,
 * io/mesh_io.c, then glpgp_mesh_create's validation), with the properties of
 * fuzz_mesh_file.h. */
#include "fuzz_mesh_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_mesh_file(".obj", ".obj", data, size);
}
