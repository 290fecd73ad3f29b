/* solver/amg.c: the aggregation multigrid preconditioner of the Newton
 * systems and the flexible CG that uses it, written once against the backend
 * table (glpgp/backend.h, ops amg_*). Design (docs/numerics.md, "Multigrid
 * preconditioner", has the reasoning and the measurements):
 *
 * Near-null space. Along the phase mode dz = i alpha z the Newton matrix A is
 * a Laplacian in alpha (no mass), along the amplitude mode dz = beta z it has
 * the penalty's mass ~ 1/eps^2. Both modes are the complex multiples of the
 * current oscillator: the span of [z, iz] per vertex. The tentative
 * prolongation of an aggregate J maps its 2 coarse unknowns (one complex
 * number u) to  x_i = c_i u  on its members, c_i = z_i / ||z||_J: a scaled
 * rotation per vertex (the block [[cr, -ci], [ci, cr]]), i.e. the vertex's
 * 2x2 block rotated into the frame of z_i; [z, iz] restricted to J is then
 * exactly P times (||z||_J, 0) and (0, ||z||_J). Vertices with z_i = 0
 * (vortex cores) have c_i = 0 (left to the smoother); an aggregate with
 * ||z||_J = 0 is dead (identity coarse row). On level l >= 1 the frame is
 * the aggregate amplitude ||f||_J (a real number), so the coarse near-null
 * vectors stay exactly reproduced on every level. For the quadratic solves
 * (naive PGP, inv4e2 = 0) the near-null space is the local plane wave
 * exp(i w.x), w = 2 pi W / h: those frames are exp(i w_J . (x_i - x_J)) per
 * aggregate (w_J from the mean field of J, x_J its centroid), on every level;
 * for the guiding-field Laplacian they are constant.
 *
 * Structure, once per (mesh, Dirichlet set), on the host: each level
 * aggregates its graph by two passes of pairwise matching (Notay's AGMG
 * idea: the unmatched node with the fewest unmatched neighbours takes its
 * strongest unmatched neighbour; fine edge weights 1, coarse weights the
 * number of fine edges between two aggregates, which keeps aggregates
 * compact): aggregates of about 4 nodes, coarse graph = quotient graph.
 * Dirichlet vertices are on no coarser level (their identity rows are solved
 * exactly by the smoother). Coarsening stops at o->amg_coarse nodes. The
 * coarse patterns and the Galerkin index maps (coarse block <- list of fine
 * blocks, gather form) are built here and uploaded once (amg_setup).
 *
 * Values, per Newton step (glpgp_amg_update), on the device: weights c from
 * the frames, A_{l+1} = P^T A_l P (one pass over A_l's blocks through the
 * map: unsmoothed aggregation), l1-Jacobi smoothers M_i = A_ii +
 * (sum_{j != i} ||A_ij||_2) I weighted by o->amg_weight (1.5): M >= A, so the
 * sweep converges for any SPD A with a weight below 2 and needs no
 * eigenvalue estimate when z changes; the same formula stays usable on the
 * indefinite exact Hessian. The coarsest matrix (2 * amg_coarse unknowns at
 * most) is read back, inverted on the host by LU with complete pivoting
 * (pivots below 1e-12 of the largest are dropped: a generalised inverse,
 * which handles the exact gauge null vector of an oscillator without
 * Dirichlet vertices and the indefinite exact Hessian), and uploaded: the
 * coarse solve is one dense matrix-vector product on the device, no host
 * round trip per cycle.
 *
 * Cycle: on level l, amg_pre sweeps of l1-Jacobi from 0, restriction of the
 * residual, coarse correction, prolongation, amg_post sweeps. The coarse
 * correction on a level that is not the coarsest is a K-cycle (Notay &
 * Vassilevski): two flexible-CG steps on A_{l+1} preconditioned by the cycle
 * on l+1 (o->amg_cycle = VCYCLE, or a level below o->amg_kcycle_min nodes:
 * one plain visit). The coefficients of those steps stay in the backend's
 * scalar registers (amg_kcombine): no host round trip inside a cycle.
 * Unsmoothed aggregation needs the K-cycle: V-cycle counts grow with the
 * number of levels (docs/numerics.md has the counts). The preconditioner is
 * not a fixed linear operator, so the outer iteration is flexible CG
 * (FCG(1)): one extra dot product per iteration compared with CG. */
#include "amg_internal.h"

#include "glpgp/util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- one instance of the hierarchy on a backend ---------------------- */

typedef struct amg_level {
    int n;
    /* device vectors (2n doubles): K-cycle and smoothing work */
    glpgp_vec *b, *e, *v, *w, *r2, *d, *wd, *tmp;
    glpgp_vec *phase;          /* plane-wave frame of this level (NULL: none) */
} amg_level;

struct glpgp_amg {
    glpgp_backend *b;
    const glpgp_amg_structure *s; /* the structure: b->amg_shared, or own */
    glpgp_amg_structure *own;  /* built for this instance alone (no shared one fits) */
    int cycle, pre, post, check, maxit;
    int kmin;                  /* levels below this many nodes: V-cycle */
    int L;
    amg_level lev[GLPGP_AMG_MAX_LEVELS];
    glpgp_vec *r, *z, *p, *q;  /* flexible CG */
    int has_phase;
    int warned;                /* the Jacobi fallback of glpgp_linear_solve was logged */
    int sync;                  /* glpgp_options.phase_sync */
    int fuse;                  /* the fused visit halves (amg_presmooth_restrict, amg_prolong_smooth):
                                  where launches cost (b->launch_bound); elsewhere the single ops,
                                  which compute each smoothed / prolonged value once where the fused
                                  ones recompute it for every neighbour (reference: +44% of those
                                  ops' instructions, a 20% slower hard-domain sweep) */
    glpgp_amg_info info;
};


/* whether the coarse correction on level c (0 < c < L-1) is a K-cycle */
int glpgp_amg_kcycle_min(const glpgp_backend *b, const glpgp_options *o)
{
    if (o->amg_kcycle_min >= 0) return o->amg_kcycle_min;
    return b && b->launch_bound ? GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND : 0;
}

static int kcycle_level(const glpgp_amg *a, int c)
{
    return a->cycle == GLPGP_AMG_KCYCLE && a->lev[c].n >= a->kmin;
}

/* The plane-wave frames of the quadratic problems: node i of level l in
 * aggregate J gets exp(i (2 pi / h) W_J . (x_i - x_J)), W_J the normalised
 * sum of the field over J's fine vertices, x_J its centroid; uploaded as
 * a->lev[l].phase. */
static glpgp_status wave_frames(glpgp_amg *a, const double *w, double h)
{
    const glpgp_amg_structure *s = a->s;
    glpgp_backend *b = a->b;
    const double k = 2.0 * GLPGP_PI / h;
    double *cur = NULL, *nxt = NULL, *ph = NULL;
    glpgp_status st = GLPGP_OK;
    const size_t n0 = (size_t)2 * s->lev[0].n;
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n0, sizeof(double), &cur), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n0, sizeof(double), &nxt), out);
    GLPGP_CHECK_GOTO(st, glpgp_malloc(n0, sizeof(double), &ph), out);
    memcpy(cur, w, n0 * sizeof(double));
    for (int l = 0; l + 1 < a->L; l++) {
        const amg_slevel *lv = &s->lev[l], *nx = &s->lev[l + 1];
        /* field sums of the aggregates */
        for (int J = 0; J < nx->n; J++) {
            double sx = 0.0, sy = 0.0;
            for (int p = lv->aptr[J]; p < lv->aptr[J + 1]; p++) {
                sx += cur[2 * lv->amem[p]];
                sy += cur[2 * lv->amem[p] + 1];
            }
            nxt[2 * J] = sx;
            nxt[2 * J + 1] = sy;
        }
        for (int i = 0; i < lv->n; i++) {
            const int J = lv->agg[i];
            const double wx = nxt[2 * J], wy = nxt[2 * J + 1], wn = hypot(wx, wy);
            ph[2 * i] = 1.0;
            ph[2 * i + 1] = 0.0;
            if (!(wn > 0.0)) continue;
            const double dx = lv->pos[2 * i] - nx->pos[2 * J], dy = lv->pos[2 * i + 1] - nx->pos[2 * J + 1];
            const double t = k * (wx * dx + wy * dy) / wn;
            ph[2 * i] = cos(t);
            ph[2 * i + 1] = sin(t);
        }
        GLPGP_CHECK_GOTO(st, b->ops->vec_create(b, (size_t)2 * lv->n, &a->lev[l].phase), out);
        GLPGP_CHECK_GOTO(st, b->ops->vec_write(b, a->lev[l].phase, ph), out);
        double *t = cur;
        cur = nxt;
        nxt = t;
    }
out:
    free(cur);
    free(nxt);
    free(ph);
    return st;
}


int glpgp_amg_supported(const glpgp_backend *b)
{
    const glpgp_backend_ops *o = b->ops;
    return o->amg_setup && o->amg_values && o->amg_coarse_invert &&
           o->amg_smooth && o->amg_restrict && o->amg_prolong && o->amg_coarse_solve &&
           o->amg_spmv_dots && o->amg_dots && o->amg_axpby && o->amg_kcombine && o->amg_get_scalars;
}

void glpgp_amg_destroy(glpgp_amg **pa)
{
    if (!pa || !*pa) return;
    glpgp_amg *a = *pa;
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *o = b->ops;
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) {
        amg_level *v = &a->lev[l];
        glpgp_vec **vs[] = {&v->b, &v->e, &v->v, &v->w, &v->r2, &v->d, &v->wd, &v->tmp, &v->phase};
        for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) o->vec_destroy(b, vs[k]);
    }
    o->vec_destroy(b, &a->r);
    o->vec_destroy(b, &a->z);
    o->vec_destroy(b, &a->p);
    o->vec_destroy(b, &a->q);
    glpgp_amg_structure_destroy(&a->own);
    free(a);
    *pa = NULL;
}

/* Upload the structure (amg_setup; a backend that holds it already, key
 * s, keeps it) and create the device work vectors. */
static glpgp_status instantiate(glpgp_amg *a, const glpgp_options *o)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    const glpgp_amg_structure *s = a->s;
    const glpgp_system *sys = b->sys;
    glpgp_amg_layout lay;
    memset(&lay, 0, sizeof lay);
    lay.nlevels = a->L;
    lay.weight = o->amg_weight;
    lay.pre = a->pre;
    lay.post = a->post;
    lay.key = s;
    for (int l = 1; l + 1 < a->L; l++) lay.kcycle[l] = (unsigned char)kcycle_level(a, l);
    for (int l = 0; l < a->L; l++) {
        const amg_slevel *lv = &s->lev[l];
        glpgp_amg_level *d = &lay.lev[l];
        d->n = lv->n;
        d->nnzb = lv->nnzb;
        d->rowptr = l ? lv->rowptr : NULL;
        d->col = l ? lv->col : sys->col;
        d->diag = l ? lv->diag : sys->diag;
        if (l + 1 < a->L) {
            d->agg = lv->agg;
            d->aptr = lv->aptr;
            d->amem = lv->amem;
            d->gptr = lv->gptr;
            d->gsrc = lv->gsrc;
        }
    }
    GLPGP_CHECK(op->amg_setup(b, &lay));
    for (int l = 0; l < a->L; l++) {
        amg_level *lv = &a->lev[l];
        const size_t n2 = (size_t)2 * lv->n;
        if (l + 1 < a->L) GLPGP_CHECK(op->vec_create(b, n2, &lv->tmp));
        if (l >= 1) {
            GLPGP_CHECK(op->vec_create(b, n2, &lv->b));
            GLPGP_CHECK(op->vec_create(b, n2, &lv->e));
        }
        if (l >= 1 && l + 1 < a->L && kcycle_level(a, l)) {
            glpgp_vec **vs[] = {&lv->v, &lv->w, &lv->r2, &lv->d, &lv->wd};
            for (size_t k = 0; k < sizeof vs / sizeof vs[0]; k++) GLPGP_CHECK(op->vec_create(b, n2, vs[k]));
        }
    }
    const size_t n0 = (size_t)2 * sys->nv;
    GLPGP_CHECK(op->vec_create(b, n0, &a->r));
    GLPGP_CHECK(op->vec_create(b, n0, &a->z));
    GLPGP_CHECK(op->vec_create(b, n0, &a->p));
    GLPGP_CHECK(op->vec_create(b, n0, &a->q));
    return GLPGP_OK;
}

glpgp_status glpgp_amg_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                              const double *w, double h, glpgp_amg **out)
{
    (void)dir; /* the frames vanish at the backend's own Dirichlet flags (set_field) */
    *out = NULL;
    const glpgp_system *sys = b->sys;
    if (!sys) return GLPGP_FAIL(GLPGP_ERR_ARG, "multigrid: backend not set up");
    if (!glpgp_amg_supported(b))
        return GLPGP_FAIL(GLPGP_ERR_UNSUPPORTED, "the %s backend has no multigrid ops", b->ops->name);
    const double t0 = glpgp_now();
    glpgp_status st = GLPGP_OK;
    glpgp_amg *a = NULL;
    GLPGP_CHECK(glpgp_calloc(1, sizeof *a, &a));
    a->b = b;
    a->cycle = o->amg_cycle;
    a->pre = o->amg_pre;
    a->post = o->amg_post;
    a->kmin = glpgp_amg_kcycle_min(b, o);
    a->check = o->amg_check;
    a->maxit = o->amg_maxit < o->cg_max ? o->amg_maxit : o->cg_max;
    a->has_phase = w != NULL && h > 0.0 && sys->mesh->xy != NULL; /* a surface: no plane waves of a global x */
    a->sync = o->phase_sync;
    a->fuse = b->launch_bound;
    /* the structure: the one shared for this system, else this instance's own */
    const glpgp_amg_structure *sh = b->amg_shared;
    if (sh && sh->sys == sys && sh->coarse == o->amg_coarse && sh->max_levels == o->amg_max_levels) {
        a->s = sh;
    } else {
        GLPGP_CHECK_GOTO(st, glpgp_amg_structure_create(sys, o, &a->own), fail);
        a->s = a->own;
    }
    a->L = a->s->L;
    for (int l = 0; l < a->L; l++) a->lev[l].n = a->s->lev[l].n;
    GLPGP_CHECK_GOTO(st, instantiate(a, o), fail);
    if (a->has_phase) GLPGP_CHECK_GOTO(st, wave_frames(a, w, h), fail);

    /* facts */
    glpgp_amg_info *in = &a->info;
    in->nlevels = a->L;
    for (int l = 0; l < a->L; l++) {
        in->n[l] = a->s->lev[l].n;
        in->nnzb[l] = a->s->lev[l].nnzb;
    }
    in->operator_complexity = a->s->operator_complexity;
    in->grid_complexity = a->s->grid_complexity;
    in->shared = a->own == NULL;
    in->seconds_structure = glpgp_now() - t0;
    *out = a;
    return GLPGP_OK;
fail:
    glpgp_amg_destroy(&a);
    return st;
}


void glpgp_amg_get_info(const glpgp_amg *a, glpgp_amg_info *info) { *info = a->info; }

/* glpgp_amg_update (spd = 0) and glpgp_amg_update_spd (spd = 1: the coarse
 * operator is symmetric PSD, see spd_inverse) */
static glpgp_status update_run(glpgp_amg *a, const glpgp_vec *x, int spd);

/* timed as the per-step numeric setup (glpgp/timers.h) */
static glpgp_status update(glpgp_amg *a, const glpgp_vec *x, int spd)
{
    const int prev = glpgp_timer_enter(a->b, GLPGP_TM_NUMERIC);
    const glpgp_status st = update_run(a, x, spd);
    glpgp_tm_leave(a->b, a->sync, prev);
    return st;
}

static glpgp_status update_run(glpgp_amg *a, const glpgp_vec *x, int spd)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    const double t0 = glpgp_now();
    const glpgp_vec *frames[GLPGP_AMG_MAX_LEVELS];
    for (int l = 0; l < GLPGP_AMG_MAX_LEVELS; l++) frames[l] = NULL;
    /* GL: frame = the oscillator on level 0, amplitudes below; quadratic
     * problems: the plane-wave phases on every level (or constants) */
    if (x)
        frames[0] = x;
    else if (a->has_phase)
        for (int l = 0; l + 1 < a->L; l++) frames[l] = a->lev[l].phase;
    GLPGP_CHECK(op->amg_values(b, frames));
    const double t1 = glpgp_now();
    /* the coarse operator on the backend (a non-finite coarsest matrix shows
     * in t[GLPGP_AMG_SLOT_STATUS] at the solvers' first read: no round trip) */
    GLPGP_CHECK(op->amg_coarse_invert(b, spd));
    const double t2 = glpgp_now();
    a->info.seconds_values += t2 - t0;
    a->info.seconds_coarse += t2 - t1;
    a->info.updates++;
    return GLPGP_OK;
}

glpgp_status glpgp_amg_update(glpgp_amg *a, const glpgp_vec *x) { return update(a, x, 0); }

glpgp_status glpgp_amg_update_spd(glpgp_amg *a, const glpgp_vec *x) { return update(a, x, 1); }

/* ---- the cycle ---------------------------------------------------------- */

static const glpgp_amg_coef ONE = {-1, -1, 1.0}, ZERO = {-1, -1, 0.0};

static glpgp_amg_coef ratio(int num, int den, double sign)
{
    glpgp_amg_coef c = {num, den, sign};
    return c;
}

static glpgp_status cycle(glpgp_amg *a, int l, const glpgp_vec *r, glpgp_vec *out, int sym);


/* e[c] <- approximate solution of A_c e = b[c]; sym: the symmetric cycle
 * of glpgp_amg_apply_spd (a W-visit where the layout has a K-cycle, a plain
 * visit elsewhere; never the backend's fused coarse correction unless the
 * layout is itself a symmetric V-cycle) */
static glpgp_status coarse_correction(glpgp_amg *a, int c, int sym)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    amg_level *lv = &a->lev[c];
    if (op->amg_coarse_correction) {
        /* the backend may run this level and all below itself (same sequence) */
        int done = 0;
        GLPGP_CHECK(op->amg_coarse_correction(b, c, sym, lv->b, lv->e, &done));
        if (done) return GLPGP_OK;
    }
    if (c == a->L - 1) return op->amg_coarse_solve(b, lv->b, lv->e);
    if (sym && kcycle_level(a, c)) {
        /* symmetric cycle on a K-cycle level: a W-visit, two stationary
         * steps of the cycle on c (fixed and symmetric, unlike the K-cycle's
         * Krylov steps; positive definite when B_c A_c < 2, which holds on
         * the positive semi-definite hierarchy of glpgp_amg_update_spd):
         *   e = B b;  r2 = b - A e;  d = B r2;  e <- e + d   (e = (2B - BAB) b) */
        const int S = GLPGP_AMG_KSLOT(c);
        const glpgp_amg_coef MINUS = {-1, -1, -1.0};
        GLPGP_CHECK(cycle(a, c, lv->b, lv->e, 1));
        GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->e, lv->w, NULL, NULL, S));
        GLPGP_CHECK(op->amg_axpby(b, ONE, lv->b, ZERO, lv->r2));
        GLPGP_CHECK(op->amg_axpby(b, MINUS, lv->w, ONE, lv->r2));
        GLPGP_CHECK(cycle(a, c, lv->r2, lv->d, 1));
        return op->amg_axpby(b, ONE, lv->d, ONE, lv->e);
    }
    if (sym || !kcycle_level(a, c)) return cycle(a, c, lv->b, lv->e, sym);
    /* K-cycle: two flexible-CG steps on A_c, preconditioned by the cycle on c
     *   v = B b;  w = A v;  rho1 = v.w;  alpha1 = v.b;  r2 = b - (alpha1/rho1) w
     *   d = B r2; wd = A d; beta = d.wd; gamma = d.w;   alpha2 = d.r2
     *   e = combination of v and d (amg_kcombine) */
    const int S = GLPGP_AMG_KSLOT(c);
    GLPGP_CHECK(cycle(a, c, lv->b, lv->v, 0));
    GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->v, lv->w, lv->b, NULL, S));
    GLPGP_CHECK(op->amg_axpby(b, ONE, lv->b, ZERO, lv->r2));
    GLPGP_CHECK(op->amg_axpby(b, ratio(S + 1, S, -1.0), lv->w, ONE, lv->r2));
    GLPGP_CHECK(cycle(a, c, lv->r2, lv->d, 0));
    GLPGP_CHECK(op->amg_spmv_dots(b, c, lv->d, lv->wd, lv->w, lv->r2, S + 2));
    return op->amg_kcombine(b, lv->v, lv->d, lv->e, S);
}

/* out <- B_l r on level l < L-1: `pre` sweeps of l1-Jacobi from 0 (none:
 * x = 0), coarse correction, `post` sweeps. The iterate alternates between
 * tmp and out, starting so that the last write lands in out.
 * sym: max(pre, post) sweeps before and after, W- or plain visits below
 * (the symmetric cycle of glpgp_amg_apply_spd). */
static glpgp_status cycle(glpgp_amg *a, int l, const glpgp_vec *r, glpgp_vec *out, int sym)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    amg_level *lv = &a->lev[l];
    glpgp_vec *buf[2] = {lv->tmp, out};
    const int nu = a->pre > a->post ? a->pre : a->post;
    const int pre = sym ? nu : a->pre, post = sym ? nu : a->post;
    const int writes = (pre > 0 ? pre : 1) + post;
    int k = writes % 2; /* buf[k] receives the first write */
    glpgp_vec *cur = buf[k];
    if (pre == 1 && a->fuse && op->amg_presmooth_restrict) {
        /* x <- M^-1 r;  b_{l+1} <- P^T (r - A x), in one pass */
        GLPGP_CHECK(op->amg_presmooth_restrict(b, l, r, cur, a->lev[l + 1].b));
    } else if (pre > 0) {
        /* x <- M^-1 r, then x <- x + M^-1 (r - A x) */
        GLPGP_CHECK(op->amg_smooth(b, l, r, NULL, cur));
        for (int s = 1; s < pre; s++) {
            k ^= 1;
            GLPGP_CHECK(op->amg_smooth(b, l, r, cur, buf[k]));
            cur = buf[k];
        }
        /* b_{l+1} <- P^T (r - A x) */
        GLPGP_CHECK(op->amg_restrict(b, l, r, cur, a->lev[l + 1].b));
    } else {
        /* x <- 0;  b_{l+1} <- P^T r */
        GLPGP_CHECK(op->amg_axpby(b, ZERO, cur, ZERO, cur));
        GLPGP_CHECK(op->amg_restrict(b, l, r, NULL, a->lev[l + 1].b));
    }
    /* e_{l+1} ~ A_{l+1}^-1 b_{l+1};  x <- x + P e */
    GLPGP_CHECK(coarse_correction(a, l + 1, sym));
    int s = 0;
    if (post > 0 && a->fuse && op->amg_prolong_smooth) {
        /* x <- x + P e and the first post-sweep, in one pass */
        k ^= 1;
        GLPGP_CHECK(op->amg_prolong_smooth(b, l, a->lev[l + 1].e, cur, r, buf[k]));
        cur = buf[k];
        s = 1;
    } else {
        GLPGP_CHECK(op->amg_prolong(b, l, a->lev[l + 1].e, cur));
    }
    for (; s < post; s++) {
        k ^= 1;
        GLPGP_CHECK(op->amg_smooth(b, l, r, cur, buf[k]));
        cur = buf[k];
    }
    return GLPGP_OK;
}

glpgp_status glpgp_amg_apply(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z)
{
    return cycle(a, 0, r, z, 0);
}

glpgp_status glpgp_amg_apply_spd(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z)
{
    return cycle(a, 0, r, z, 1);
}

/* ---- flexible CG -------------------------------------------------------- */

enum { T_ZQ = 0, T_PQ = 2, T_PR = 3, T_RR = 4, T_N = 8 };

/* FCG(1) on NEWTON; *nonfinite <- 1 when it stopped on a non-finite value */
static glpgp_status fcg_run(glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                            glpgp_cg_info *info, int *nonfinite)
{
    glpgp_backend *b = a->b;
    const glpgp_backend_ops *op = b->ops;
    glpgp_vec *r = a->r, *z = a->z, *p = a->p, *q = a->q;
    double t[T_N];
    int k = 0;
    *nonfinite = 0;
    info->iterations = 0;
    info->relres = 0.0;
    info->reason = GLPGP_CG_CONVERGED;
    if (maxit > a->maxit) maxit = a->maxit;
    /* x <- 0;  r <- b */
    GLPGP_CHECK(op->amg_axpby(b, ZERO, x, ZERO, x));
    GLPGP_CHECK(op->copy(b, r, rhs));
    GLPGP_CHECK(op->amg_dots(b, r, r, NULL, T_RR));
    GLPGP_CHECK(op->amg_get_scalars(b, t, T_N));
    b->n_sync++;
    if (t[GLPGP_AMG_SLOT_STATUS] != 0.0) { /* the coarsest matrix was not finite: no preconditioner */
        *nonfinite = 1;
        info->reason = GLPGP_CG_BREAKDOWN;
        return GLPGP_OK;
    }
    const double bnorm = sqrt(t[T_RR]);
    if (!isfinite(bnorm)) return GLPGP_FAIL(GLPGP_ERR_NUMERIC, "CG right-hand side is not finite");
    if (bnorm == 0.0) return GLPGP_OK;
    double rel = 1.0;
    for (k = 1; k <= maxit; k++) {
        /* z <- B r;  p <- z - (z.q / p.q) p  (q = A p of the previous step) */
        GLPGP_CHECK(cycle(a, 0, r, z, 0));
        if (k == 1) {
            GLPGP_CHECK(op->amg_axpby(b, ONE, z, ZERO, p));
        } else {
            GLPGP_CHECK(op->amg_dots(b, z, q, NULL, T_ZQ));
            GLPGP_CHECK(op->amg_axpby(b, ONE, z, ratio(T_ZQ, T_PQ, -1.0), p));
        }
        /* q <- A p;  alpha = p.r / p.q;  x += alpha p;  r -= alpha q */
        GLPGP_CHECK(op->amg_spmv_dots(b, 0, p, q, r, NULL, T_PQ));
        GLPGP_CHECK(op->amg_axpby(b, ratio(T_PR, T_PQ, 1.0), p, ONE, x));
        GLPGP_CHECK(op->amg_axpby(b, ratio(T_PR, T_PQ, -1.0), q, ONE, r));
        GLPGP_CHECK(op->amg_dots(b, r, r, NULL, T_RR));
        b->n_spmv++;
        b->n_cg_iter++;
        if (k % a->check == 0 || k == maxit) {
            GLPGP_CHECK(op->amg_get_scalars(b, t, T_N));
            b->n_sync++;
            if (!isfinite(t[T_RR]) || !isfinite(t[T_PQ])) {
                *nonfinite = 1;
                info->reason = GLPGP_CG_BREAKDOWN;
                break;
            }
            if (!(t[T_PQ] > 0.0)) {
                info->reason = GLPGP_CG_BREAKDOWN;
                break;
            }
            rel = sqrt(t[T_RR]) / bnorm;
            if (rel <= rtol) break;
        }
    }
    info->iterations = glpgp_cg_verdict(info, k, maxit, rel, rtol);
    return GLPGP_OK;
}

glpgp_status glpgp_fcg(glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                       glpgp_cg_info *info)
{
    int nonfinite;
    const int prev = glpgp_timer_enter(a->b, GLPGP_TM_LINEAR);
    const glpgp_status st = fcg_run(a, rhs, x, rtol, maxit, info, &nonfinite);
    glpgp_timer_leave(a->b, prev);
    return st;
}

static glpgp_status linear_solve(glpgp_backend *b, glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                                 int maxit, int check, glpgp_cg_info *info);

/* timed as a linear solve (glpgp/timers.h) */
glpgp_status glpgp_linear_solve(glpgp_backend *b, glpgp_amg *a, const glpgp_vec *rhs,
                                glpgp_vec *x, double rtol, int maxit, int check,
                                glpgp_cg_info *info)
{
    const int prev = glpgp_timer_enter(b, GLPGP_TM_LINEAR);
    const glpgp_status st = linear_solve(b, a, rhs, x, rtol, maxit, check, info);
    glpgp_timer_leave(b, prev);
    return st;
}

static glpgp_status linear_solve(glpgp_backend *b, glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                                 int maxit, int check, glpgp_cg_info *info)
{
    if (b->ops->linear_solve) {
        /* the backend's own solver (PETSc: KSP); the reason values are glpgp_cg_reason's */
        int it = 0, reason = 0;
        double relres = 0.0;
        GLPGP_CHECK(b->ops->linear_solve(b, rhs, x, rtol, maxit, &it, &relres, &reason));
        info->iterations = it;
        info->relres = relres;
        info->reason = reason == 0 ? GLPGP_CG_CONVERGED : reason == 1 ? GLPGP_CG_MAXIT : GLPGP_CG_BREAKDOWN;
        b->n_cg_iter += it;
        b->n_spmv += it;
        return GLPGP_OK;
    }
    if (!a) return glpgp_cg(b, rhs, x, rtol, maxit, check, info);
    int nonfinite = 0;
    GLPGP_CHECK(fcg_run(a, rhs, x, rtol, maxit, info, &nonfinite));
    if (!nonfinite) return GLPGP_OK;
    /* the preconditioner produced a non-finite value (p.Ap <= 0 is a
     * property of the matrix and is reported as is): redo with Jacobi */
    if (!a->warned)
        glpgp_log(GLPGP_LOG_WARNING, "multigrid preconditioner produced a non-finite value; "
                                     "using Jacobi-PCG for this system");
    a->warned = 1;
    const int it = info->iterations;
    GLPGP_CHECK(glpgp_cg(b, rhs, x, rtol, maxit, check, info));
    info->iterations += it;
    return GLPGP_OK;
}

static int glpgp_amg_try_update_mode(glpgp_amg *a, const glpgp_vec *x, int spd, const char *what);

glpgp_amg *glpgp_amg_try_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                                const double *w, double h, const char *what)
{
    glpgp_amg *a = NULL;
    if (o->precond != GLPGP_PRECOND_AMG) return NULL;
    if (b->ops->linear_solve) return NULL; /* the backend's own solver preconditions */
    const int prev = glpgp_timer_enter(b, GLPGP_TM_STRUCTURE);
    const glpgp_status st = glpgp_amg_create(b, o, dir, w, h, &a);
    glpgp_tm_leave(b, o->phase_sync, prev);
    if (st != GLPGP_OK) {
        glpgp_log(GLPGP_LOG_WARNING, "%s: multigrid setup failed (%s); using Jacobi-PCG", what,
                  glpgp_error_message());
        glpgp_error_clear();
        return NULL;
    }
    const glpgp_amg_info *in = &a->info;
    char kc[64] = "";
    if (a->cycle == GLPGP_AMG_KCYCLE && a->kmin > 0)
        snprintf(kc, sizeof kc, ", K-cycle on levels of >= %d nodes", a->kmin);
    glpgp_log(GLPGP_LOG_DEBUG,
              "%s: multigrid %d levels, %d -> %d nodes, operator complexity %.3f, %s %.3f s%s",
              what, in->nlevels, in->n[0], in->n[in->nlevels - 1], in->operator_complexity,
              in->shared ? "shared structure, instance" : "structure", in->seconds_structure, kc);
    return a;
}

int glpgp_amg_try_update(glpgp_amg *a, const glpgp_vec *x, const char *what)
{
    return glpgp_amg_try_update_mode(a, x, 0, what);
}

int glpgp_amg_try_update_spd(glpgp_amg *a, const glpgp_vec *x, const char *what)
{
    return glpgp_amg_try_update_mode(a, x, 1, what);
}

static int glpgp_amg_try_update_mode(glpgp_amg *a, const glpgp_vec *x, int spd, const char *what)
{
    if (update(a, x, spd) == GLPGP_OK) return 1;
    glpgp_log(GLPGP_LOG_WARNING, "%s: multigrid setup failed (%s); using Jacobi-PCG", what,
              glpgp_error_message());
    glpgp_error_clear();
    return 0;
}
