/* core/vec.c: glpgp_grow_int (glpgp/internal/vec.h), glpgp_grow for arrays
 * whose lengths are ints. */
#include "glpgp/internal/vec.h"

#include <limits.h>

glpgp_status glpgp_grow_int(void *ptr, int *cap, int need, size_t elem)
{
    if (need < 0) return GLPGP_FAIL(GLPGP_ERR_NOMEM, "array size overflows");
    size_t c = *cap > 0 ? (size_t)*cap : 0;
    GLPGP_CHECK(glpgp_grow(ptr, &c, (size_t)need, elem));
    *cap = c > INT_MAX ? INT_MAX : (int)c;
    return GLPGP_OK;
}
