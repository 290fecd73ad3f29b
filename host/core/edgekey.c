/* core/edgekey.c: the (edge key, slot) order of glpgp/internal/edgekey.h. */
#include "glpgp/internal/edgekey.h"

int glpgp_ekv_cmp(const void *x, const void *y)
{
    const glpgp_ekv *a = x, *b = y;
    return a->k < b->k ? -1 : a->k > b->k ? 1 : (a->slot > b->slot) - (a->slot < b->slot);
}
