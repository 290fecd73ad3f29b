/* glpgp/internal/heap.h: a binary min-heap of (key, id) pairs (core/heap.c),
 * the priority queue of the Dijkstra-like sweeps (the size field's
 * gradation on meshes and surfaces, the quad closing's strip search).
 * Ties leave in a fixed order (the order of the pushes and pops alone), so
 * every run pops the same sequence. Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_HEAP_H
#define GLPGP_INTERNAL_HEAP_H

#include "glpgp/status.h"

#include <stddef.h>

typedef struct glpgp_heap_item {
    double key;
    int id;
} glpgp_heap_item;

typedef struct glpgp_heap {
    glpgp_heap_item *a;
    size_t n, cap;
} glpgp_heap;

/* Room for at least cap items without growing (optional; a push grows). */
glpgp_status glpgp_heap_reserve(glpgp_heap *h, size_t cap);
/* Add (key, id). */
glpgp_status glpgp_heap_push(glpgp_heap *h, double key, int id);
/* Remove and return the item of the smallest key (h->n > 0). */
glpgp_heap_item glpgp_heap_pop(glpgp_heap *h);
/* Free the storage; the heap is empty and may be reused. */
void glpgp_heap_free(glpgp_heap *h);

#endif
