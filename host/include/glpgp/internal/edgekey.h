/* glpgp/internal/edgekey.h: an undirected edge (a, b) as one sortable 64-bit
 * key, and (key, slot) pairs sorted by key then slot (core/edgekey.c): how
 * the quad layer's repair, region, fill and chords and the solver's
 * refinement match the two sides of an edge. Internal: not installed.
 * Layer: core. */
#ifndef GLPGP_INTERNAL_EDGEKEY_H
#define GLPGP_INTERNAL_EDGEKEY_H

/* (min(a, b), max(a, b)) packed: high 32 bits the smaller vertex (a, b >= 0). */
static inline unsigned long long glpgp_edge_key(int a, int b)
{
    unsigned lo = (unsigned)(a < b ? a : b), hi = (unsigned)(a < b ? b : a);
    return ((unsigned long long)lo << 32) | hi;
}

typedef struct glpgp_ekv {
    unsigned long long k;
    int slot;
} glpgp_ekv;

/* qsort comparison of glpgp_ekv: by k, then by slot. */
int glpgp_ekv_cmp(const void *x, const void *y);

#endif
