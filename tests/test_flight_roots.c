/* The closed-form flight's safe step inside a radius (lib/sim/flight_roots.c): the fast search
 * (td_sim_flight_inside_until) must give the plain 30-step bisection's answer bit for bit on every
 * input, including crossings that lie on a point of the bisection's grid (where the sign of F as
 * computed is rounding noise), grazing orbits and a start at the radius; the proof that a split
 * cannot beat the best step so far (td_sim_flight_outside_from) must never be wrong; and the modal
 * sums' real product (flight_mul) must be C's complex product; two observations summed side by side
 * (td_sim_flight_observe2) must be the single sums' bits, and the state summed over the kept modes'
 * columns (td_sim_flight_peek, as materialise) each state's row of V times the modal coordinates. */
#include "td_test.h"

#include "sim/flight_internal.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NCASES 60000

typedef struct inside_case {
    double R, m, a, p[2], v[2], hi;
} inside_case;

static double uniform(uint64_t *s)
{
    return (double)(td_test_splitmix(s) >> 11) * 0x1p-53;
}

/* 10^x for x uniform in [lo, hi] */
static double decades(uint64_t *s, double lo, double hi)
{
    return pow(10.0, lo + (hi - lo) * uniform(s));
}

/* A point of the bisection's grid on [0, hi]: the midpoint after `levels` random halvings, computed
 * as the bisection computes it. */
static double grid_point(uint64_t *s, double hi)
{
    double lo = 0.0, mid = 0.5 * hi;
    int i, levels = (int)(td_test_splitmix(s) % 30);
    for (i = 0; i <= levels; i++) {
        mid = 0.5 * (lo + hi);
        if (td_test_splitmix(s) & 1)
            lo = mid;
        else
            hi = mid;
    }
    return mid;
}

/* |p + v t| as the search computes it */
static double length_at(const inside_case *c, double t)
{
    return hypot(c->p[0] + c->v[0] * t, c->p[1] + c->v[1] * t);
}

/* A random orbit near a clearance R of 10 um to 1 mm: an offset up to 1.2 R in any direction,
 * speeds of 1 um/s to 10 m/s, accelerations up to 1e5 m/s^2 (or none), fast modes' amplitude m;
 * one in three with R set so that F crosses zero on a point of the bisection's grid, one in three
 * starting at the radius (F(0) zero or a few ulps), half of these moving along it. */
static inside_case random_case(uint64_t *s)
{
    static const double his[4] = {1e-2, 1e-3, 2.5e-4, 0.0};
    inside_case c;
    double r, th = 2.0 * TD_PI * uniform(s), ph = 2.0 * TD_PI * uniform(s), sp;
    int kind = (int)(td_test_splitmix(s) % 6);
    c.hi = his[td_test_splitmix(s) % 4];
    if (c.hi == 0.0)
        c.hi = decades(s, -6.0, -2.0);
    c.R = decades(s, -5.0, -3.0);
    r = 1.2 * c.R * uniform(s);
    c.p[0] = r * cos(th), c.p[1] = r * sin(th);
    sp = decades(s, -6.0, 1.0);
    c.v[0] = sp * cos(ph), c.v[1] = sp * sin(ph);
    c.a = (td_test_splitmix(s) % 4 == 0) ? 0.0 : decades(s, -3.0, 5.0);
    c.m = (td_test_splitmix(s) % 3 == 0) ? 0.0 : 0.3 * c.R * decades(s, -14.0, 0.0);
    if (kind <= 1) { /* the crossing on a grid point */
        double t = grid_point(s, c.hi);
        c.R = c.m + 0.5 * c.a * t * t + length_at(&c, t);
    } else if (kind >= 2 && kind <= 3) { /* a start at the radius, moving along it with kind 3 */
        if (kind == 3)
            c.v[0] = -sp * sin(th), c.v[1] = sp * cos(th), c.a *= 1e-6;
        c.R = c.m + length_at(&c, 0.0);
        c.R += c.R * 0x1p-52 * (double)(td_test_splitmix(s) % 4);
    }
    return c;
}

static double fast(const inside_case *c, double hi)
{
    return td_sim_flight_inside_until(c->R, c->m, c->a, c->p, c->v, hi);
}

static double plain(const inside_case *c, double hi)
{
    return td_sim_flight_inside_bisect(c->R, c->m, c->a, c->p, c->v, hi);
}

/* Every random case: the same bits as the plain bisection. */
static void test_same_as_bisection(void **state)
{
    uint64_t seed = 31;
    int i, differ = 0, inside = 0;
    (void)state;
    for (i = 0; i < NCASES; i++) {
        inside_case c = random_case(&seed);
        double x = fast(&c, c.hi), y = plain(&c, c.hi);
        if (memcmp(&x, &y, sizeof x) != 0) {
            if (differ++ < 5)
                print_error("case %d: R %a m %a a %a p %a %a v %a %a hi %a: fast %a, bisection %a\n", i, c.R, c.m, c.a,
                            c.p[0], c.p[1], c.v[0], c.v[1], c.hi, x, y);
        }
        inside += y > 0.0 && y < c.hi;
    }
    assert_int_equal(differ, 0);
    assert_true(inside > NCASES / 4); /* most cases cross inside the step: the search proper is tested */
}

/* Where the split is proven unable to beat t, no longest step gives a larger answer; and a clear
 * case is proven: F(tau) = 5e-4 - 0.1 tau - 5 tau^2 crosses at 4.5e-3 s. */
static void test_outside_from(void **state)
{
    static const double p[2] = {5e-4, 0.0}, v[2] = {0.1, 0.0};
    uint64_t seed = 17;
    int i, proven = 0, tried = 0;
    (void)state;
    assert_true(td_sim_flight_outside_from(1e-3, 0.0, 10.0, p, v, 5e-3));
    assert_false(td_sim_flight_outside_from(1e-3, 0.0, 10.0, p, v, 4e-3));
    assert_true(td_sim_flight_inside_until(1e-3, 0.0, 10.0, p, v, 1e-2) < 5e-3);
    for (i = 0; i < NCASES / 4; i++) {
        inside_case c = random_case(&seed);
        double r = plain(&c, c.hi), t = r * (1.0 + 1e-9 * decades(&seed, 0.0, 6.0));
        if (td_test_splitmix(&seed) % 4 == 0)
            t = c.hi * uniform(&seed);
        if (!(r > 0.0 && r < c.hi))
            continue;
        tried++;
        if (!td_sim_flight_outside_from(c.R, c.m, c.a, c.p, c.v, t))
            continue;
        proven++;
        assert_true(plain(&c, c.hi) <= t);
        assert_true(plain(&c, 2.0 * c.hi) <= t);
        assert_true(plain(&c, t) <= t);
        assert_true(fast(&c, 3.0 * c.hi) <= t);
    }
    assert_true(proven > tried / 2);
}

/* Degenerate inputs: no motion, a start outside, a NaN, a negative a: the bisection's answers. */
static void test_degenerate(void **state)
{
    static const double zero[2] = {0.0, 0.0}, p[2] = {2e-4, 0.0}, v[2] = {0.0, 1e-3};
    const double nan2[2] = {NAN, 0.0};
    double x, y;
    (void)state;
    assert_true(fast(&(inside_case){1e-4, 0.0, 0.0, {0.0, 0.0}, {0.0, 0.0}, 1e-2}, 1e-2) == 1e-2);
    assert_true(td_sim_flight_inside_until(1e-4, 0.0, 0.0, p, zero, 1e-2) == 0.0);
    x = td_sim_flight_inside_until(3e-4, 0.0, 1.0, p, v, 1e-2);
    y = td_sim_flight_inside_bisect(3e-4, 0.0, 1.0, p, v, 1e-2);
    assert_memory_equal(&x, &y, sizeof x);
    x = td_sim_flight_inside_until(3e-4, 0.0, 1.0, nan2, v, 1e-2);
    y = td_sim_flight_inside_bisect(3e-4, 0.0, 1.0, nan2, v, 1e-2);
    assert_memory_equal(&x, &y, sizeof x);
    assert_false(td_sim_flight_outside_from(3e-4, 0.0, 1.0, nan2, v, 1e-3));
    x = td_sim_flight_inside_until(3e-4, 0.0, -50.0, p, v, 1e-2); /* F convex: no proof, the bisection */
    y = td_sim_flight_inside_bisect(3e-4, 0.0, -50.0, p, v, 1e-2);
    assert_memory_equal(&x, &y, sizeof x);
    assert_false(td_sim_flight_outside_from(3e-4, 0.0, -50.0, p, v, 1e-3));
}

/* The modal sums' product without the NaN check: C's complex product's bits for finite factors of
 * any size (each part of x y one rounding of ac - bd, ad + bc). */
static void test_product(void **state)
{
    uint64_t seed = 5;
    int i, differ = 0;
    (void)state;
    for (i = 0; i < NCASES; i++) {
        double complex x = decades(&seed, -20.0, 20.0) * (uniform(&seed) - 0.5) +
                           I * decades(&seed, -20.0, 20.0) * (uniform(&seed) - 0.5);
        double complex y = decades(&seed, -20.0, 20.0) * (uniform(&seed) - 0.5) +
                           I * decades(&seed, -20.0, 20.0) * (uniform(&seed) - 0.5);
        double complex z = x * y;
        double xy[2], re = creal(z), im = cimag(z);
        flight_mul(x, y, xy);
        differ += memcmp(&xy[0], &re, sizeof re) != 0 || memcmp(&xy[1], &im, sizeof im) != 0;
    }
    assert_int_equal(differ, 0);
}

#define OBS_MODES 37

static double complex random_complex(uint64_t *s, double lo, double hi)
{
    return decades(s, lo, hi) * (uniform(s) - 0.5) + I * decades(s, lo, hi) * (uniform(s) - 0.5);
}

/* A flight of OBS_MODES modes (every other one kept) with two random observations, propagated to t
 * as td_sim_flight_propagate leaves it (e, |e| grow, the phase at t_e); its arrays in `mem`. */
static void random_flight(uint64_t *s, td_sim_flight *f, flight_obs obs[2], double complex *mem, double *rmem,
                          int *keep, double t)
{
    int j, o;
    memset(f, 0, sizeof *f);
    f->nz = OBS_MODES;
    f->lam = mem, f->e = mem + OBS_MODES;
    f->ae = rmem;
    f->keep = keep;
    for (j = 0; j < OBS_MODES; j++) {
        f->lam[j] = -decades(s, 0.0, 3.0) + I * decades(s, 1.0, 4.0);
        f->e[j] = random_complex(s, -3.0, 0.0);
        f->ae[j] = cabs(f->e[j]) * (1.0 + uniform(s));
        if (j % 2 == 0)
            f->keep[f->nkeep++] = j;
    }
    f->omega = decades(s, 1.0, 3.0), f->tf = uniform(s), f->t_e = t;
    f->ep = td_sim_flight_phase(f, t);
    f->nobs = 2, f->obs = obs;
    for (o = 0; o < 2; o++) {
        flight_obs *b = &obs[o];
        memset(b, 0, sizeof *b);
        b->c = mem + (2 + o) * OBS_MODES;
        b->m0 = rmem + (1 + 3 * o) * OBS_MODES, b->m1 = b->m0 + OBS_MODES, b->m2 = b->m1 + OBS_MODES;
        for (j = 0; j < OBS_MODES; j++) {
            b->c[j] = random_complex(s, -8.0, 2.0);
            b->m0[j] = cabs(b->c[j]), b->m1[j] = b->m0[j] * cabs(f->lam[j]), b->m2[j] = b->m1[j] * cabs(f->lam[j]);
        }
        b->h0 = random_complex(s, -6.0, 0.0), b->hp = random_complex(s, -6.0, 0.0),
        b->hm = random_complex(s, -6.0, 0.0);
        b->h0_abs = cabs(b->h0), b->h_abs = cabs(b->hp) + cabs(b->hm);
        b->seen_t = NAN;
    }
}

/* td_sim_flight_observe2 gives (and keeps) td_sim_flight_observe's bits for each observation, with
 * none, one or both kept already. */
static void test_observe_pair(void **state)
{
    uint64_t seed = 11;
    double complex mem[4 * OBS_MODES];
    double rmem[7 * OBS_MODES];
    int keep[OBS_MODES], i, differ = 0;
    (void)state;
    for (i = 0; i < 2000; i++) {
        td_sim_flight f;
        flight_obs obs[2];
        flight_val one[2], two[2];
        double t = uniform(&seed);
        random_flight(&seed, &f, obs, mem, rmem, keep, t);
        one[0] = td_sim_flight_observe(&f, 0, t);
        one[1] = td_sim_flight_observe(&f, 1, t);
        obs[0].seen_t = i % 3 == 1 ? t : NAN; /* kept already: 0, 1 or neither */
        obs[1].seen_t = i % 3 == 2 ? t : NAN;
        td_sim_flight_observe2(&f, 0, 1, t, &two[0], &two[1]);
        differ += memcmp(one, two, sizeof one) != 0;
        differ +=
            memcmp(&obs[0].seen, &one[0], sizeof one[0]) != 0 || memcmp(&obs[1].seen, &one[1], sizeof one[1]) != 0;
        differ += obs[0].seen_t != t || obs[1].seen_t != t;
    }
    assert_int_equal(differ, 0);
}

#define SUM_STATES 23
#define SUM_MODES 17

/* The state from the flight's kept-column sum (td_sim_flight_peek, materialise's sum) is, bit for
 * bit, each state's row of V times the weighted modal coordinates, the terms in mode order (the sum
 * the flight made before its columns were stored apart), for even and odd numbers of kept modes. */
static void test_state_sum(void **state)
{
    static double complex V[SUM_STATES * SUM_STATES], mem[5 * SUM_STATES], work[2 * SUM_STATES];
    static double vr[SUM_STATES * SUM_STATES], vi[SUM_STATES * SUM_STATES], weight[SUM_STATES];
    int keep[SUM_STATES], i, j, k, n, differ = 0;
    uint64_t seed = 17;
    (void)state;
    for (n = 0; n < 400; n++) {
        td_sim s;
        td_sim_flight f;
        double y[SUM_STATES], t = uniform(&seed);
        memset(&s, 0, sizeof s);
        memset(&f, 0, sizeof f);
        s.flight = &f;
        f.nz = SUM_STATES, f.anchored = 1, f.V = V, f.vr = vr, f.vi = vi, f.keep = keep, f.weight = weight;
        f.lam = mem, f.d = mem + SUM_STATES, f.p0 = mem + 2 * SUM_STATES, f.pp = mem + 3 * SUM_STATES,
        f.pm = mem + 4 * SUM_STATES;
        f.omega = decades(&seed, 1.0, 3.0), f.tf = uniform(&seed), f.ta = uniform(&seed);
        for (j = 0; j < SUM_STATES * SUM_STATES; j++)
            V[j] = random_complex(&seed, -4.0, 1.0);
        for (j = 0; j < SUM_STATES; j++) {
            f.lam[j] = -decades(&seed, 0.0, 3.0) + I * decades(&seed, 1.0, 4.0);
            f.d[j] = random_complex(&seed, -6.0, 0.0), f.p0[j] = random_complex(&seed, -6.0, 0.0);
            f.pp[j] = random_complex(&seed, -6.0, 0.0), f.pm[j] = random_complex(&seed, -6.0, 0.0);
            weight[j] = uniform(&seed) < 0.5 ? 1.0 : 2.0;
        }
        for (j = 0; j < SUM_MODES - n % 2; j++) /* kept: random columns */
            keep[f.nkeep++] = j + (int)(uniform(&seed) * (SUM_STATES - SUM_MODES));
        for (k = 0; k < f.nkeep; k++) /* the kept columns apart, as kept_columns stores them */
            for (i = 0; i < SUM_STATES; i++) {
                vr[k * SUM_STATES + i] = creal(V[i * SUM_STATES + keep[k]]);
                vi[k * SUM_STATES + i] = cimag(V[i * SUM_STATES + keep[k]]);
            }
        assert_int_equal(td_sim_flight_peek(&s, t, y, (double *)(void *)work), 1);
        for (i = 0; i < SUM_STATES; i++) { /* work holds the weighted modal coordinates */
            const double complex *row = V + i * SUM_STATES;
            double z = 0.0;
            for (k = 0; k < f.nkeep; k++)
                z += creal(row[keep[k]]) * creal(work[k]) - cimag(row[keep[k]]) * cimag(work[k]);
            differ += memcmp(&z, &y[i], sizeof z) != 0;
        }
    }
    assert_int_equal(differ, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_bisection), cmocka_unit_test(test_outside_from),
        cmocka_unit_test(test_degenerate),        cmocka_unit_test(test_product),
        cmocka_unit_test(test_observe_pair),      cmocka_unit_test(test_state_sum),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
