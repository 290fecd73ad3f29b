/* glpgp/glpgp.h: the umbrella header of glpgp's stable public API: one
 * #include <glpgp/glpgp.h> gives a program everything a user of the library
 * calls: errors and logging (status.h), the version, option descriptors,
 * meshes, built-in shapes and surfaces, the solve and its result, cross
 * fields, the backends (reference, OpenCL, PETSc, the cross-check), quad
 * meshes, every reader and writer (io.h), the distributed solve on MPI ranks
 * (distributed.h) and the image layer (pictures,
 * mask domains, Gmsh). The headers under glpgp/internal/ (the Newton step,
 * CG, the multigrid, the test switches) are the library's own plumbing:
 * not installed, no stability promise. Layer: image (it includes all). */
#ifndef GLPGP_GLPGP_H
#define GLPGP_GLPGP_H

#include "glpgp/status.h"
#include "glpgp/version.h"
#include "glpgp/kinds.h"
#include "glpgp/optdesc.h"
#include "glpgp/phase.h"
#include "glpgp/timers.h"
#include "glpgp/util.h"
#include "glpgp/json.h"
#include "glpgp/mesh.h"
#include "glpgp/shapes.h"
#include "glpgp/surface.h"
#include "glpgp/result.h"
#include "glpgp/cross.h"
#include "glpgp/solve.h"
#include "glpgp/surfsolve.h"
#include "glpgp/backends.h"
#include "glpgp/quads.h"
#include "glpgp/io.h"
#include "glpgp/distributed.h"
#include "glpgp/image.h"

#endif
