/* test_select.c: order statistics without sorting (glpgp_select_double,
 * glpgp_median_double in glpgp/util.h) against qsort, exactly: every k of
 * random arrays of 1 .. 300 values (few distinct values too, so ties and
 * runs of equal keys are exercised), sorted, reversed and constant inputs,
 * the partition property around a[k], the even-length median as the mean of
 * the middle two, and a million values (the solver's median |z|). */
#include "testutil.h"

#include "glpgp/util.h"

#include <stdlib.h>
#include <string.h>

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* every k of a (n values) against the sorted copy; the partition holds */
static void check_all(const double *a, size_t n)
{
    double *s = malloc(n * sizeof *s), *w = malloc(n * sizeof *w);
    memcpy(s, a, n * sizeof *s);
    qsort(s, n, sizeof *s, cmp);
    for (size_t k = 0; k < n; k++) {
        memcpy(w, a, n * sizeof *w);
        const double v = glpgp_select_double(w, n, k);
        CHECK(v == s[k] && w[k] == s[k]);
        for (size_t i = 0; i < n; i++) CHECK(i < k ? w[i] <= v : i > k ? w[i] >= v : 1);
        /* a permutation: the multiset is unchanged */
        qsort(w, n, sizeof *w, cmp);
        CHECK(memcmp(w, s, n * sizeof *w) == 0);
    }
    memcpy(w, a, n * sizeof *w);
    const double med = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    CHECK(glpgp_median_double(w, n) == med);
    free(s);
    free(w);
}

int main(void)
{
    double a[300];
    for (int rep = 0; rep < 3; rep++)
        for (size_t n = 1; n <= 300; n += (n < 40 ? 1 : 37)) {
            for (size_t i = 0; i < n; i++) a[i] = rep == 0 ? tu_rand() : rep == 1 ? (double)(int)(4 * tu_rand()) : -tu_rand();
            check_all(a, n);
        }
    for (size_t i = 0; i < 200; i++) a[i] = (double)i; /* sorted */
    check_all(a, 200);
    for (size_t i = 0; i < 200; i++) a[i] = (double)(200 - i); /* reversed */
    check_all(a, 200);
    for (size_t i = 0; i < 200; i++) a[i] = 0.5; /* constant */
    check_all(a, 200);
    /* organ pipe and two values alternating: adversarial for simple pivots */
    for (size_t i = 0; i < 201; i++) a[i] = i < 100 ? (double)i : (double)(200 - i);
    check_all(a, 201);
    for (size_t i = 0; i < 100; i++) a[i] = (double)(i % 2);
    check_all(a, 100);

    /* a million values: the median and the 10th percentile */
    const size_t n = 1000000;
    double *big = malloc(n * sizeof *big), *s = malloc(n * sizeof *s);
    for (size_t i = 0; i < n; i++) big[i] = s[i] = 1.0 + 0.01 * (tu_rand() - 0.5);
    qsort(s, n, sizeof *s, cmp);
    const size_t k10 = (size_t)((n - 1) * 0.1);
    CHECK(glpgp_select_double(big, n, k10) == s[k10]);
    CHECK(glpgp_median_double(big, n) == 0.5 * (s[n / 2 - 1] + s[n / 2]));
    free(big);
    free(s);
    TEST_DONE();
}
