/* hard_domains.h: CAD-like planar test domains for the quad extraction, as
 * polygons with holes in units of the target quad size H (H = 1), with an
 * optional local mesh size per point (graded meshes). Header-only: used by
 * tests/quads/test_repair.c (in-process, meshed by Gmsh through
 * glpgp_mesh_polygons) and by bench/hard_domains.c (writes Triangle .poly
 * files for `glpgp mesh` / `glpgp solve`, bench/gmsh_compare.sh).
 *
 * hd_build(name, e, &p): the domain `name` with point size e (the wanted
 * triangle edge; graded domains use e near the feature and up to 40 e far
 * away). Names: see HD_NAMES. */
#ifndef GLPGP_HARD_DOMAINS_H
#define GLPGP_HARD_DOMAINS_H

#include "glpgp/image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define HD_PI 3.14159265358979323846

/* slot      rectangle with a slot 0.3 H wide cut into it (narrower than H)
 * strip     a strip 8 H long, 0.12 H wide (much narrower than H)
 * smallhole square with a hole of radius 0.08 H and one of 0.3 H
 * wedge20   a 20-degree wedge closed by an arc
 * cusp      a crescent between two circles (tips of about 16 degrees) with a
 *           0.5-degree spike cut into its outer side
 * graded    NACA 0012 airfoil (chord 3 H) in a 14 x 10 H box: sizes e at the
 *           airfoil, 40 e at the box corners (edge ratio >= 40)
 * perforated plate 6 x 6 H with 25 holes of radius 0.12 H
 * ibeam     I-beam section: flanges 6 x 0.8 H, web 0.25 H thick
 * motor     lamination: annulus (radii 2.2 H / 4.5 H) with 8 slots 0.3 H
 *           wide and 1.2 H deep between teeth, filleted slot bottoms
 * fillet    L-shape with a fillet (radius 1.2 H) at the re-entrant corner
 *           and spline-rounded outer corners (polylines)
 * crack     square with a crack: a notch 0.01 H wide and 2.5 H long
 * airfoil   NACA 0012 (chord 3 H) at 4 degrees of attack in a circular far
 *           field (radius 8 H, sizes 12 e there), its sides as a CAD export
 *           gives them: 300 points each, cosine-spaced whatever e (8e-5 H
 *           apart at the sharp trailing edge, where Gmsh joined three of them
 *           into one flat triangle of 179.99 degrees: cut off by
 *           glpgp_mesh_polygons)
 * gasket    rounded rectangle 10 x 4 H, ten bolt holes of radius 0.4 H 0.15 H
 *           from its long sides (thin ligaments), a central hole
 * lamination disk of radius 5 H with a bore and 16 round holes of radius
 *           0.35 H near the rim (holes smaller than H all around)
 * comb      twelve teeth 0.2 H wide, 3 H long, 0.6 H apart on a base
 * star      twelve spikes between radii 1 and 3 H (tips of about 12 degrees)
 * keyhole   a disk of radius 3 H whose hole of radius 1 H opens to the rim by
 *           a slot 0.3 H wide */
#define HD_NAMES \
    "slot strip smallhole wedge20 cusp graded perforated ibeam motor fillet crack airfoil gasket lamination comb " \
    "star keyhole"
/* The failure classes of issue 27, beyond HD_NAMES (bench/hard_sweep.sh
 * runs both lists and totals them apart):
 * strip100  a strip 8 H long, 0.01 H wide (100 x narrower than H)
 * cusp01    a square with a spike of 0.1 degrees and a slit 0.1 degrees open
 * graded100 NACA 0012 (chord 1 H) in a 40 x 30 H far field graded 100 x
 * sieve     a plate with 144 holes of radius 0.1 H, 0.6 H apart
 * stator    an annulus (3 / 5 H) with 24 slots 0.15 H wide from its bore
 * wing3     slat, main element and flap (gaps 0.05 H) in a far field
 *           graded 100 x */
#define HD_NAMES_27 "strip100 cusp01 graded100 sieve stator wing3"

typedef struct hd_poly {
    int n, cap_l;      /* loops */
    int *start;        /* n + 1 */
    double *xy, *size; /* points */
    int np, cap_p;
} hd_poly;

static void hd_point(hd_poly *p, double x, double y, double s)
{
    if (p->np == p->cap_p) {
        p->cap_p = p->cap_p ? 2 * p->cap_p : 256;
        p->xy = realloc(p->xy, sizeof(double) * 2 * (size_t)p->cap_p);
        p->size = realloc(p->size, sizeof(double) * (size_t)p->cap_p);
    }
    p->xy[2 * p->np] = x;
    p->xy[2 * p->np + 1] = y;
    p->size[p->np] = s;
    p->np++;
}

static void hd_begin(hd_poly *p)
{
    if (p->n + 2 > p->cap_l) {
        p->cap_l = p->cap_l ? 2 * p->cap_l : 16;
        p->start = realloc(p->start, sizeof(int) * (size_t)p->cap_l);
    }
    p->start[p->n] = p->np;
}
static void hd_end(hd_poly *p)
{
    p->n++;
    p->start[p->n] = p->np;
}

/* Segment from the last point to (x, y), points every <= s (the end point included). */
static void hd_line_to(hd_poly *p, double x, double y, double s)
{
    double x0 = p->xy[2 * (p->np - 1)], y0 = p->xy[2 * (p->np - 1) + 1];
    int k = (int)ceil(hypot(x - x0, y - y0) / s);
    if (k < 1) k = 1;
    for (int i = 1; i <= k; i++) hd_point(p, x0 + (x - x0) * i / k, y0 + (y - y0) * i / k, s);
}
/* Closed polygon through the corners c[0..n) (counter-clockwise or not). */
static void hd_polygon(hd_poly *p, const double *c, int n, double s)
{
    hd_begin(p);
    hd_point(p, c[0], c[1], s);
    for (int i = 1; i < n; i++) hd_line_to(p, c[2 * i], c[2 * i + 1], s);
    hd_line_to(p, c[0], c[1], s);
    p->np--; /* the first point is not repeated */
    hd_end(p);
}
static void hd_circle(hd_poly *p, double cx, double cy, double r, double s)
{
    int k = (int)ceil(2 * HD_PI * r / s);
    if (k < 8) k = 8;
    hd_begin(p);
    for (int i = 0; i < k; i++) hd_point(p, cx + r * cos(2 * HD_PI * i / k), cy + r * sin(2 * HD_PI * i / k), s);
    hd_end(p);
}
/* Arc (center, radius, angles a0 -> a1, end point included, start not). */
static void hd_arc(hd_poly *p, double cx, double cy, double r, double a0, double a1, double s)
{
    int k = (int)ceil(fabs(a1 - a0) * r / s);
    if (k < 2) k = 2;
    for (int i = 1; i <= k; i++) {
        double a = a0 + (a1 - a0) * i / k;
        hd_point(p, cx + r * cos(a), cy + r * sin(a), s);
    }
}

static void hd_free(hd_poly *p)
{
    free(p->start);
    free(p->xy);
    free(p->size);
    memset(p, 0, sizeof *p);
}

/* NACA 0012 half thickness at x in [0, 1]. */
static double hd_naca(double x)
{
    return 0.6 * (0.2969 * sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x - 0.1036 * x * x * x * x);
}

/* Build domain `name` (H = 1) with triangle edge e. Returns 0 on an unknown name. */
static int hd_build(const char *name, double e, hd_poly *p)
{
    memset(p, 0, sizeof *p);
    if (!strcmp(name, "slot")) {
        double c[] = {0, 0, 6, 0, 6, 4, 3.15, 4, 3.15, 1.2, 2.85, 1.2, 2.85, 4, 0, 4};
        hd_polygon(p, c, 8, e);
    } else if (!strcmp(name, "strip")) {
        double c[] = {0, 0, 8, 0, 8, 0.12, 0, 0.12};
        hd_polygon(p, c, 4, fmin(e, 0.04));
    } else if (!strcmp(name, "smallhole")) {
        double c[] = {0, 0, 5, 0, 5, 5, 0, 5};
        hd_polygon(p, c, 4, e);
        hd_circle(p, 1.7, 2.3, 0.08, fmin(e, 0.05));
        hd_circle(p, 3.4, 3.1, 0.3, fmin(e, 0.1));
    } else if (!strcmp(name, "wedge20")) {
        double a = 10.0 * HD_PI / 180.0, R = 7.0;
        hd_begin(p);
        hd_point(p, 0, 0, e);
        hd_line_to(p, R * cos(-a), R * sin(-a), e);
        hd_arc(p, 0, 0, R, -a, a, e);
        hd_line_to(p, 0, 0, e);
        p->np--;
        hd_end(p);
    } else if (!strcmp(name, "cusp")) {
        /* crescent: disk (0,0,3) minus disk (0.9,0,2.5): tips where they cross */
        double R = 3.0, cx = 0.9, r = 2.5;
        double xi = (R * R - r * r + cx * cx) / (2 * cx), yi = sqrt(R * R - xi * xi);
        double A0 = atan2(yi, xi), A1 = atan2(yi, xi - cx);
        hd_begin(p);
        hd_point(p, xi, yi, e);
        /* outer arc counter-clockwise from the upper tip to the lower tip, with a
         * thin spike cut in at the far left */
        int k = (int)ceil((2 * HD_PI - 2 * A0) * R / e);
        int spike = 0;
        for (int i = 1; i < k; i++) {
            double a = A0 + (2 * HD_PI - 2 * A0) * i / k;
            if (!spike && a >= HD_PI) { /* spike tip: 2 atan(0.005 / 1.2) = 0.5 deg */
                double ds = 0.005 / R;
                hd_point(p, R * cos(HD_PI - ds), R * sin(HD_PI - ds), e);
                hd_point(p, -R + 1.2, 0.0, e);
                hd_point(p, R * cos(HD_PI + ds), R * sin(HD_PI + ds), e);
                spike = 1;
                if (a - HD_PI < 0.3 * (2 * HD_PI - 2 * A0) / k) continue;
            }
            hd_point(p, R * cos(a), R * sin(a), e);
        }
        hd_point(p, xi, -yi, e);
        /* inner arc clockwise back to the upper tip */
        hd_arc(p, cx, 0, r, -A1, -(2 * HD_PI - A1), e);
        p->np--;
        hd_end(p);
    } else if (!strcmp(name, "graded")) {
        double big = 40 * e;
        double c[] = {-5, -5, 9, -5, 9, 5, -5, 5};
        hd_begin(p);
        for (int i = 0; i < 4; i++) {
            hd_point(p, c[2 * i], c[2 * i + 1], big);
            /* a few points along the sides, sized by distance to the airfoil */
            double nx = c[2 * ((i + 1) % 4)], ny = c[2 * ((i + 1) % 4) + 1];
            for (int k = 1; k < 4; k++) {
                double x = c[2 * i] + (nx - c[2 * i]) * k / 4, y = c[2 * i + 1] + (ny - c[2 * i + 1]) * k / 4;
                hd_point(p, x, y, big);
            }
        }
        hd_end(p);
        /* airfoil, chord 3 from (0, 0) to (3, 0), clockwise (a hole) */
        hd_begin(p);
        int k = (int)ceil(3.0 / e);
        for (int i = 0; i < k; i++) { /* upper side from the trailing edge to the leading edge, cosine spacing */
            double t = 0.5 * (1 + cos(HD_PI * i / k));
            hd_point(p, 3 * t, 3 * hd_naca(t), e);
        }
        for (int i = 0; i < k; i++) {
            double t = 0.5 * (1 - cos(HD_PI * i / k));
            hd_point(p, 3 * t, -3 * hd_naca(t), e);
        }
        hd_end(p);
    } else if (!strcmp(name, "airfoil")) {
        hd_begin(p);
        for (int i = 0; i < 96; i++) {
            double a = 2 * HD_PI * i / 96;
            hd_point(p, 1.5 + 8 * cos(a), 8 * sin(a), 12 * e);
        }
        hd_end(p);
        /* clockwise (a hole): upper side from the trailing edge, lower side back */
        const int k = 300;
        const double ca = cos(4 * HD_PI / 180), sa = sin(4 * HD_PI / 180);
        hd_begin(p);
        for (int i = 0; i < 2 * k; i++) {
            double t = i < k ? 0.5 * (1 + cos(HD_PI * i / k)) : 0.5 * (1 - cos(HD_PI * (i - k) / k));
            double x = 3 * t, y = (i < k ? 3 : -3) * hd_naca(t);
            hd_point(p, x * ca + y * sa, -x * sa + y * ca, e);
        }
        hd_end(p);
    } else if (!strcmp(name, "perforated")) {
        double c[] = {0, 0, 6, 0, 6, 6, 0, 6};
        hd_polygon(p, c, 4, e);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) hd_circle(p, 1 + i, 1 + j + 0.1 * (i % 2), 0.12, fmin(e, 0.06));
    } else if (!strcmp(name, "ibeam")) {
        double w = 0.125;
        double c[] = {0, 0, 6, 0, 6, 0.8, 3 + w, 0.8, 3 + w, 4.2, 6, 4.2, 6, 5, 0, 5, 0, 4.2, 3 - w, 4.2, 3 - w, 0.8, 0, 0.8};
        hd_polygon(p, c, 12, fmin(e, 0.08));
    } else if (!strcmp(name, "motor")) {
        double Ro = 4.5, Ri = 2.2, depth = 1.2, half = 0.15;
        int ns = 8;
        /* outer circle */
        hd_circle(p, 0, 0, Ro, e);
        /* bore with slots, clockwise (a hole): slot i at angle -2 pi i / ns */
        hd_begin(p);
        double da = half / Ri; /* slot half width as an angle on the bore */
        double step = 2 * HD_PI / ns;
        hd_point(p, Ri * cos(step - da), Ri * sin(step - da), e);
        for (int i = 0; i < ns; i++) {
            double a = -step * i;
            hd_arc(p, 0, 0, Ri, a + step - da, a + da, e); /* bore, clockwise */
            double ux = cos(a), uy = sin(a), vx = -sin(a), vy = cos(a);
            double bx = (Ri + depth) * ux, by = (Ri + depth) * uy;
            hd_line_to(p, bx + half * vx, by + half * vy, fmin(e, 0.1));
            for (int k = 1; k < 8; k++) { /* round slot bottom */
                double t = HD_PI * k / 8;
                hd_point(p, bx + half * (cos(t) * vx + sin(t) * ux), by + half * (cos(t) * vy + sin(t) * uy),
                         fmin(e, 0.05));
            }
            hd_point(p, bx - half * vx, by - half * vy, fmin(e, 0.05));
            hd_line_to(p, Ri * cos(a - da), Ri * sin(a - da), fmin(e, 0.1));
        }
        p->np--; /* the last point repeats the first */
        hd_end(p);
    } else if (!strcmp(name, "fillet")) {
        double rf = 1.2, rc = 0.4;
        hd_begin(p);
        /* L: (0,0) (6,0) (6,3) (3,3) (3,6) (0,6), re-entrant corner at (3,3) */
        hd_point(p, rc, 0, e);
        hd_line_to(p, 6 - rc, 0, e);
        hd_arc(p, 6 - rc, rc, rc, -HD_PI / 2, 0, fmin(e, 0.1));
        hd_line_to(p, 6, 3 - rc, e);
        hd_arc(p, 6 - rc, 3 - rc, rc, 0, HD_PI / 2, fmin(e, 0.1));
        hd_line_to(p, 3 + rf, 3, e);
        hd_arc(p, 3 + rf, 3 + rf, rf, -HD_PI / 2, -HD_PI, e); /* concave fillet */
        hd_line_to(p, 3, 6 - rc, e);
        hd_arc(p, 3 - rc, 6 - rc, rc, 0, HD_PI / 2, fmin(e, 0.1));
        hd_line_to(p, rc, 6, e);
        hd_arc(p, rc, 6 - rc, rc, HD_PI / 2, HD_PI, fmin(e, 0.1));
        hd_line_to(p, 0, rc, e);
        hd_arc(p, rc, rc, rc, HD_PI, 1.5 * HD_PI, fmin(e, 0.1));
        p->np--;
        hd_end(p);
    } else if (!strcmp(name, "crack")) {
        double c[] = {0, 0, 5, 0, 5, 5, 0, 5, 0, 2.505, 2.5, 2.505, 2.5, 2.495, 0, 2.495};
        hd_polygon(p, c, 8, e);
    } else if (!strcmp(name, "gasket")) {
        /* rounded rectangle 10 x 4 (corner radius 0.5), ten bolt holes of
         * radius 0.4 whose ligaments to the long sides are 0.15 wide, a
         * central hole of radius 1 */
        const double r = 0.5;
        hd_begin(p);
        hd_point(p, r, 0, e);
        hd_line_to(p, 10 - r, 0, e);
        hd_arc(p, 10 - r, r, r, -HD_PI / 2, 0, fmin(e, 0.1));
        hd_line_to(p, 10, 4 - r, e);
        hd_arc(p, 10 - r, 4 - r, r, 0, HD_PI / 2, fmin(e, 0.1));
        hd_line_to(p, r, 4, e);
        hd_arc(p, r, 4 - r, r, HD_PI / 2, HD_PI, fmin(e, 0.1));
        hd_line_to(p, 0, r, e);
        hd_arc(p, r, r, r, HD_PI, 1.5 * HD_PI, fmin(e, 0.1));
        p->np--;
        hd_end(p);
        for (int i = 0; i < 5; i++) {
            hd_circle(p, 1 + 2 * i, 0.55, 0.4, fmin(e, 0.05));
            hd_circle(p, 1 + 2 * i, 3.45, 0.4, fmin(e, 0.05));
        }
        hd_circle(p, 5, 2, 1.0, e);
    } else if (!strcmp(name, "lamination")) {
        /* a rotor lamination: disk of radius 5, a bore of radius 1.2, 16 round
         * holes of radius 0.35 (smaller than H) on the circle of radius 3.6 */
        hd_circle(p, 0, 0, 5, e);
        hd_circle(p, 0, 0, 1.2, e);
        for (int i = 0; i < 16; i++)
            hd_circle(p, 3.6 * cos(2 * HD_PI * i / 16), 3.6 * sin(2 * HD_PI * i / 16), 0.35, fmin(e, 0.06));
    } else if (!strcmp(name, "comb")) {
        /* a base 9.8 x 1 with twelve teeth 0.2 wide and 3 long, 0.6 apart */
        double c[2 * 52];
        int n = 0;
        c[n++] = 0, c[n++] = 0, c[n++] = 9.8, c[n++] = 0, c[n++] = 9.8, c[n++] = 4, c[n++] = 9.6, c[n++] = 4;
        c[n++] = 9.6, c[n++] = 1;
        double x = 9.6;
        for (int i = 0; i < 11; i++) {
            x -= 0.6;
            c[n++] = x, c[n++] = 1, c[n++] = x, c[n++] = 4, c[n++] = x - 0.2, c[n++] = 4, c[n++] = x - 0.2, c[n++] = 1;
            x -= 0.2;
        }
        c[n++] = 0, c[n++] = 1;
        hd_polygon(p, c, n / 2, fmin(e, 0.05));
    } else if (!strcmp(name, "star")) {
        /* twelve spikes between radii 1 and 3 (tips of about 12 degrees) */
        double c[2 * 24];
        for (int i = 0; i < 24; i++) {
            const double r = i % 2 ? 1.0 : 3.0, a = 2 * HD_PI * i / 24;
            c[2 * i] = r * cos(a);
            c[2 * i + 1] = r * sin(a);
        }
        hd_polygon(p, c, 24, e);
    } else if (!strcmp(name, "keyhole")) {
        /* a disk of radius 3 with a hole of radius 1 joined to the outside by
         * a slot 0.3 wide: one loop */
        const double a0 = asin(0.15 / 3), a1 = asin(0.15 / 1);
        hd_begin(p);
        hd_point(p, 3 * cos(a0), 3 * sin(a0), e);
        hd_arc(p, 0, 0, 3, a0, 2 * HD_PI - a0, e);
        hd_line_to(p, cos(-a1), sin(-a1), fmin(e, 0.05));
        hd_arc(p, 0, 0, 1, 2 * HD_PI - a1, a1, fmin(e, 0.1));
        hd_line_to(p, 3 * cos(a0), 3 * sin(a0), fmin(e, 0.05));
        p->np--;
        hd_end(p);
    } else if (!strcmp(name, "strip100")) { /* 100x narrower than H */
        double c[] = {0, 0, 8, 0, 8, 0.01, 0, 0.01};
        hd_polygon(p, c, 4, fmin(e, 0.01));
    } else if (!strcmp(name, "cusp01")) {
        /* a square with a spike of the domain standing on its top side (a
         * 0.1-degree tip) and a slit cut into its bottom side (0.1 degrees
         * open: the outside's cusp) */
        double t = 1.2 * tan(0.05 * HD_PI / 180.0), d = 1.5 * tan(0.05 * HD_PI / 180.0);
        double c[] = {0, 0, 2.5 - t, 0, 2.5, 1.2, 2.5 + t, 0, 5, 0, 5, 4, 2.6 + d, 4, 2.6, 5.5, 2.6 - d, 4, 0, 4};
        hd_polygon(p, c, 10, e);
    } else if (!strcmp(name, "graded100")) {
        /* NACA 0012 (chord 1 H) in a 40 x 30 H box: e at the airfoil, 100 e at the box */
        double big = 100 * e, c[] = {-15, -15, 25, -15, 25, 15, -15, 15};
        hd_begin(p);
        for (int i = 0; i < 4; i++) {
            double nx = c[2 * ((i + 1) % 4)], ny = c[2 * ((i + 1) % 4) + 1];
            for (int k = 0; k < 8; k++)
                hd_point(p, c[2 * i] + (nx - c[2 * i]) * k / 8, c[2 * i + 1] + (ny - c[2 * i + 1]) * k / 8, big);
        }
        hd_end(p);
        hd_begin(p);
        int k = (int)ceil(1.0 / e) + 4;
        for (int i = 0; i < 2 * k; i++) {
            double t = i < k ? 0.5 * (1 + cos(HD_PI * i / k)) : 0.5 * (1 - cos(HD_PI * (i - k) / k));
            hd_point(p, t, (i < k ? 1 : -1) * hd_naca(t), e);
        }
        hd_end(p);
    } else if (!strcmp(name, "sieve")) { /* 144 holes of radius 0.1 H, 0.6 H apart */
        double c[] = {0, 0, 7.8, 0, 7.8, 7.8, 0, 7.8};
        hd_polygon(p, c, 4, e);
        for (int i = 0; i < 12; i++)
            for (int j = 0; j < 12; j++) hd_circle(p, 0.6 + 0.6 * i, 0.6 + 0.6 * j + 0.05 * (i % 3), 0.1, fmin(e, 0.05));
    } else if (!strcmp(name, "stator")) {
        /* annulus (radii 3 / 5 H) with 24 slots 0.15 H wide and 1.2 H deep
         * from the bore: slots narrower than H */
        const int ns = 24;
        const double R0 = 3.0, R1 = 5.0, w = 0.075, D = 1.2;
        hd_begin(p);
        for (int i = 0; i < 96; i++) hd_point(p, R1 * cos(2 * HD_PI * i / 96), R1 * sin(2 * HD_PI * i / 96), e);
        hd_end(p);
        hd_begin(p); /* the bore with the slots, clockwise */
        for (int i = ns - 1; i >= 0; i--) {
            double a = 2 * HD_PI * i / ns, ca = cos(a), sa = sin(a), ta = -sa, tb = ca;
            double b = w / R0, a1 = a + b, a0 = a - b, an = 2 * HD_PI * (i - 1) / ns + b;
            hd_point(p, R0 * cos(a1), R0 * sin(a1), e);
            hd_point(p, (R0 + D) * ca + w * ta, (R0 + D) * sa + w * tb, fmin(e, 0.05));
            hd_point(p, (R0 + D) * ca - w * ta, (R0 + D) * sa - w * tb, fmin(e, 0.05));
            hd_point(p, R0 * cos(a0), R0 * sin(a0), e);
            for (int k = 1; k < 4; k++) {
                double u = a0 + (an - a0) * k / 4;
                hd_point(p, R0 * cos(u), R0 * sin(u), e);
            }
        }
        hd_end(p);
    } else if (!strcmp(name, "wing3")) {
        /* slat, main element and flap (NACA 0012 sections, chords 0.4, 2 and
         * 0.7 H, gaps 0.05 H) in a far field graded 100 x */
        double big = 100 * e, c[] = {-20, -15, 25, -15, 25, 15, -20, 15};
        hd_begin(p);
        for (int i = 0; i < 4; i++) {
            double nx = c[2 * ((i + 1) % 4)], ny = c[2 * ((i + 1) % 4) + 1];
            for (int k = 0; k < 6; k++)
                hd_point(p, c[2 * i] + (nx - c[2 * i]) * k / 6, c[2 * i + 1] + (ny - c[2 * i + 1]) * k / 6, big);
        }
        hd_end(p);
        const double x0[3] = {-0.47, 0.0, 2.05}, ch[3] = {0.4, 2.0, 0.7}, ang[3] = {-25, 0, 20}, y0[3] = {-0.12, 0, -0.2};
        for (int w = 0; w < 3; w++) {
            const double ca = cos(ang[w] * HD_PI / 180), sa = sin(ang[w] * HD_PI / 180);
            int k = (int)ceil(ch[w] / e) + 6;
            hd_begin(p);
            for (int i = 0; i < 2 * k; i++) {
                double t = i < k ? 0.5 * (1 + cos(HD_PI * i / k)) : 0.5 * (1 - cos(HD_PI * (i - k) / k));
                double x = ch[w] * t, y = (i < k ? ch[w] : -ch[w]) * hd_naca(t);
                hd_point(p, x0[w] + x * ca + y * sa, y0[w] - x * sa + y * ca, e);
            }
            hd_end(p);
        }
    } else {
        return 0;
    }
    return 1;
}

/* ---- random polygons with holes ---- */

/* Whether segments ab and cd cross (touching counts). */
static inline int hd_seg_hit(const double *a, const double *b, const double *c, const double *d)
{
    double d1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    double d2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
    double d3 = (d[0] - c[0]) * (a[1] - c[1]) - (d[1] - c[1]) * (a[0] - c[0]);
    double d4 = (d[0] - c[0]) * (b[1] - c[1]) - (d[1] - c[1]) * (b[0] - c[0]);
    return ((d1 >= 0) != (d2 >= 0)) && ((d3 >= 0) != (d4 >= 0));
}

/* The outer loop's corners: a star with spikes and slits; 0 when it crosses itself. */
static inline int hd_outer_loop(double (*rnd)(void), double *c, int *nc, double *rmin)
{
    int n = 6 + (int)(rnd() * 14), m = 0;
    *rmin = 1e9;
    for (int i = 0; i < n; i++) {
        double a = 2 * HD_PI * (i + 0.35 * rnd()) / n, r = 2.5 + 1.5 * rnd();
        double a1 = 2 * HD_PI * (i + 1) / n, x = r * cos(a), y = r * sin(a);
        *rmin = fmin(*rmin, r);
        c[2 * m] = x;
        c[2 * m + 1] = y;
        m++;
        double u = rnd(), mx = 2.4 * cos(0.5 * (a + a1)), my = 2.4 * sin(0.5 * (a + a1));
        double nx = cos(0.5 * (a + a1)), ny = sin(0.5 * (a + a1)), tx = -ny, ty = nx;
        if (u < 0.12) { /* a spike out, 0.5 .. 10 degrees */
            double L = 1.0 + rnd(), ang = (0.5 + 9.5 * rnd()) * HD_PI / 180, w = 2 * L * tan(0.5 * ang);
            double pts[6] = {mx - 0.5 * w * tx, my - 0.5 * w * ty, mx + L * nx, my + L * ny, mx + 0.5 * w * tx,
                             my + 0.5 * w * ty};
            memcpy(c + 2 * m, pts, sizeof pts);
            m += 3;
        } else if (u < 0.24) { /* a slit in, 0.005 .. 0.1 H wide */
            double w = 0.005 + 0.095 * rnd(), D = 0.5 + 0.8 * rnd();
            double pts[8] = {mx - 0.5 * w * tx, my - 0.5 * w * ty, mx - D * nx - 0.5 * w * tx, my - D * ny - 0.5 * w * ty,
                             mx - D * nx + 0.5 * w * tx, my - D * ny + 0.5 * w * ty, mx + 0.5 * w * tx, my + 0.5 * w * ty};
            memcpy(c + 2 * m, pts, sizeof pts);
            m += 4;
        }
    }
    for (int i = 0; i < m; i++)
        for (int j = i + 2; j < m; j++) {
            if (i == 0 && j == m - 1) continue;
            if (hd_seg_hit(c + 2 * i, c + 2 * ((i + 1) % m), c + 2 * j, c + 2 * ((j + 1) % m))) return 0;
        }
    *nc = m;
    return 1;
}

/* Distance from p to the polygon's sides. */
static inline double hd_poly_dist(const double *c, int n, double x, double y)
{
    double d = 1e9;
    for (int i = 0; i < n; i++) {
        const double *a = c + 2 * i, *b = c + 2 * ((i + 1) % n);
        double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
        double t = l2 > 0 ? ((x - a[0]) * ex + (y - a[1]) * ey) / l2 : 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        d = fmin(d, hypot(a[0] + t * ex - x, a[1] + t * ey - y));
    }
    return d;
}

static inline int hd_inside(const double *c, int n, double x, double y)
{
    int in = 0;
    for (int i = 0, j = n - 1; i < n; j = i++)
        if ((c[2 * i + 1] > y) != (c[2 * j + 1] > y) &&
            x < c[2 * j] + (y - c[2 * j + 1]) * (c[2 * i] - c[2 * j]) / (c[2 * i + 1] - c[2 * j + 1]))
            in = !in;
    return in;
}

/* A random polygon with holes (test_quads_property, glpgp-domains random):
 * a star-shaped outer loop (radii 2.5 .. 4 H) with spikes of 0.5 .. 10
 * degrees and slits 0.005 .. 0.1 H wide, up to 6 round holes of radius
 * 0.02 .. 0.8 H, 0.001 .. 0.5 H from the outer loop and each other; point
 * size e. rnd: uniform in [0, 1). 0 when the outer loop crossed itself. */
static inline int hd_random(double (*rnd)(void), hd_poly *p, double e)
{
    double c[512], rmin;
    int n = 0;
    memset(p, 0, sizeof *p);
    if (!hd_outer_loop(rnd, c, &n, &rmin)) return 0;
    hd_polygon(p, c, n, e);
    static const double gaps[4] = {1e-3, 1e-2, 0.1, 0.5};
    int nh = (int)(rnd() * 7), placed = 0;
    double hx[8], hy[8], hr[8];
    for (int t = 0; t < 60 && placed < nh; t++) {
        double r = 0.02 + 0.78 * rnd() * rnd(), gap = gaps[(int)(rnd() * 4)];
        double x = (2 * rnd() - 1) * rmin, y = (2 * rnd() - 1) * rmin;
        if (!hd_inside(c, n, x, y) || hd_poly_dist(c, n, x, y) < r + gap) continue;
        int ok = 1;
        for (int k = 0; k < placed && ok; k++) ok = hypot(x - hx[k], y - hy[k]) > r + hr[k] + gap;
        if (!ok) continue;
        hx[placed] = x;
        hy[placed] = y;
        hr[placed] = r;
        placed++;
        hd_circle(p, x, y, r, fmin(e, 0.5 * r + 0.005));
    }
    return 1;
}

/* As glpgp_polygons (areas, orientation and parents by nesting are worked
 * out by glpgp_polygons_read; here through a .poly round trip is not
 * needed: the loops are written as they are). */
static int hd_write_poly(const hd_poly *p, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return 0;
    fprintf(f, "# glpgp hard test domain (tests/quads/hard_domains.h)\n%d 2 1 0\n", p->np);
    for (int i = 0; i < p->np; i++) fprintf(f, "%d %.17g %.17g %.17g\n", i, p->xy[2 * i], p->xy[2 * i + 1], p->size[i]);
    fprintf(f, "%d 0\n", p->np);
    int k = 0;
    for (int l = 0; l < p->n; l++)
        for (int i = p->start[l]; i < p->start[l + 1]; i++) {
            int j = i + 1 < p->start[l + 1] ? i + 1 : p->start[l];
            fprintf(f, "%d %d %d\n", k++, i, j);
        }
    fprintf(f, "0\n");
    return fclose(f) == 0;
}

#endif
