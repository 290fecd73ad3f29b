/* core/heap.c: the binary min-heap of glpgp/internal/heap.h (sift up on
 * push, sift the last item down from the root on pop). */
#include "glpgp/internal/heap.h"

#include <stdlib.h>

glpgp_status glpgp_heap_reserve(glpgp_heap *h, size_t cap)
{
    GLPGP_CHECK(glpgp_grow(&h->a, &h->cap, cap, sizeof *h->a));
    return GLPGP_OK;
}

glpgp_status glpgp_heap_push(glpgp_heap *h, double key, int id)
{
    if (h->n == h->cap) GLPGP_CHECK(glpgp_grow(&h->a, &h->cap, h->n + 1, sizeof *h->a));
    size_t i = h->n++;
    while (i > 0 && h->a[(i - 1) / 2].key > key) {
        h->a[i] = h->a[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->a[i].key = key;
    h->a[i].id = id;
    return GLPGP_OK;
}

glpgp_heap_item glpgp_heap_pop(glpgp_heap *h)
{
    const glpgp_heap_item top = h->a[0], last = h->a[--h->n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= h->n) break;
        if (c + 1 < h->n && h->a[c + 1].key < h->a[c].key) c++;
        if (h->a[c].key >= last.key) break;
        h->a[i] = h->a[c];
        i = c;
    }
    if (h->n > 0) h->a[i] = last;
    return top;
}

void glpgp_heap_free(glpgp_heap *h)
{
    free(h->a);
    h->a = NULL;
    h->n = h->cap = 0;
}
