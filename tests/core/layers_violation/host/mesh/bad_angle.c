/* A mesh-layer file that includes a header of the higher backends layer with
 * angle brackets: the layer check must see it as it sees "glpgp/X.h". */
#include <glpgp/backends.h>
