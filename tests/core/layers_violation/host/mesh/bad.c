/* A mesh-layer file that includes a header of the higher solver layer: the
 * `layers_detects_violation` test runs the layer check on this tree and
 * expects it to fail. */
#include "glpgp/solve.h"
