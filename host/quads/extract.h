/* quads/extract.h: the extraction's graph (the arrangement of level lines,
 * mesh vertices and boundary, extract.c) and its planar map with the
 * clean-up of its faces (extract_map.c). Internal to the quads layer. */
#ifndef GLPGP_QUADS_EXTRACT_H
#define GLPGP_QUADS_EXTRACT_H

#include "glpgp/quads.h"

typedef struct qnode {
    double x, y;
    int vert;            /* mesh vertex, or -1 */
    unsigned char bnd;   /* on the domain boundary */
    unsigned char fixed; /* domain corner / forced corner */
} qnode;

enum { QE_BND = 1, QE_U = 2, QE_V = 4, QE_DEL = 8 };
typedef struct qedge {
    int a, b;            /* for QE_BND edges a -> b is the boundary loop direction */
    unsigned char flags;
} qedge;

typedef struct graph {
    qnode *node;
    int nn, capn;
    qedge *edge;
    int ne, cape;
} graph;


typedef struct pmap {
    int nh;          /* 2 * ne half-edges: h = 2e (a -> b), 2e + 1 (b -> a) */
    int *rot_start;  /* nn + 1 */
    int *rot;        /* half-edges by origin, counter-clockwise */
    int *rot_pos;    /* nh: index of h in rot */
    int *face;       /* nh: face of h (face on the left) */
    int nf;
    int *face_he;    /* a half-edge of each face */
    unsigned char *outer; /* nf */
    int *deg;        /* nn */
} pmap;

static inline int he_orig(const graph *g, int h) { return h & 1 ? g->edge[h >> 1].b : g->edge[h >> 1].a; }
static inline int he_dest(const graph *g, int h) { return h & 1 ? g->edge[h >> 1].a : g->edge[h >> 1].b; }

glpgp_status glpgp_xg_add_node(graph *g, double x, double y, int vert, int bnd, int *id);
glpgp_status glpgp_xg_add_edge(graph *g, int a, int b, int flags);

/* Merge every node into its union-find root (parent[]), drop the edges
 * that became loops and the duplicates. */
glpgp_status glpgp_xm_merge_nodes(graph *g, int *parent);
/* Remove dangling ends (degree-1 nodes, repeatedly). */
glpgp_status glpgp_xm_prune(graph *g);
/* The planar map of g: rotation system, faces, the outer ones. */
glpgp_status glpgp_xm_pmap_build(const graph *g, pmap *p);
void glpgp_xm_pmap_free(pmap *p);
/* The next half-edge around h's face (the face on its left). */
int glpgp_xm_face_next(const graph *g, const pmap *p, int h);
/* Corner flags of all nodes for the current map. */
void glpgp_xm_corners(const graph *g, const pmap *p, unsigned char *corner);
/* One round of the faces' clean-up (extract.c's header); *changes 0: final. */
glpgp_status glpgp_xm_cleanup_round(graph *g, const pmap *p, double h, int *changes, int *collapsed, int *promoted);

#endif
