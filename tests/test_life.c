/* The touchdown bearing's life (lib/assess: rainflow.c, life.c): the rainflow count against the
 * worked example of ASTM E1049-85 (its Fig. 6 history and Table 4 counts), the hysteresis gate,
 * and the damage law's arithmetic by hand on a short history. The count against an independent
 * implementation (the PyPI package rainflow) is tests/life/rainflow_reference.py. */
#include "td_test.h"

#include "sim/sim_internal.h"
#include "touchdown/assess.h"
#include "touchdown/case.h"

#include <math.h>
#include <string.h>

/* Cycles collected by range: count[r] for the ranges nearest the integer r in 0..15, and the totals. */
typedef struct tally {
    double count[16];
    double cycles, weighted; /* sum of counts, sum of count range^3 */
    int calls;
} tally;

static void take(void *user, double range, double mean, double count)
{
    tally *t = user;
    int r = (int)lround(range);
    (void)mean;
    assert_true(r >= 0 && r < 16);
    t->count[r] += count; /* by the nearest integer range */
    t->cycles += count;
    t->weighted += count * range * range * range;
    t->calls++;
}

static void count_history(const double *x, int n, double gate, tally *t)
{
    td_rainflow *rf = td_rainflow_create(gate, NULL);
    int i;
    assert_non_null(rf);
    memset(t, 0, sizeof *t);
    for (i = 0; i < n; i++)
        assert_int_equal(td_rainflow_add(rf, x[i], take, t, NULL), TD_OK);
    td_rainflow_residue(rf, take, t);
    assert_int_equal(td_rainflow_values(rf), n);
    td_rainflow_free(&rf);
    assert_null(rf);
}

/* ASTM E1049-85 Fig. 6: the history -2 1 -3 5 -1 3 -4 4 -2 counts (Table 4, rainflow) ranges
 * 3: 0.5, 4: 1.5, 6: 0.5, 8: 1.0, 9: 0.5 and no other; the same with samples in between (not
 * reversals), and fed in two parts with the residue asked for twice in between (it leaves the
 * counter as it was: the parts' closed cycles and the residue at the end add up to the same). */
static void test_astm_worked_example(void **state)
{
    static const double astm[] = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
    static const double dense[] = {-2, -1, 0, 1, 0.5, -3, 0, 5, 2, -1, 3, 0, -4, 4, 1, -2};
    const double want[16] = {[3] = 0.5, [4] = 1.5, [6] = 0.5, [8] = 1.0, [9] = 0.5};
    tally t, r1, r2;
    td_rainflow *rf = td_rainflow_create(0.0, NULL);
    int i;
    (void)state;
    count_history(astm, 9, 0.0, &t);
    assert_memory_equal(t.count, want, sizeof want);
    count_history(dense, 16, 0.0, &t);
    assert_memory_equal(t.count, want, sizeof want);
    memset(&t, 0, sizeof t);
    memset(&r1, 0, sizeof r1);
    memset(&r2, 0, sizeof r2);
    for (i = 0; i < 5; i++)
        assert_int_equal(td_rainflow_add(rf, astm[i], take, &t, NULL), TD_OK);
    td_rainflow_residue(rf, take, &r1);
    td_rainflow_residue(rf, take, &r2);
    assert_true(r1.calls > 0);
    assert_memory_equal(r1.count, r2.count, sizeof r1.count);
    for (; i < 9; i++)
        assert_int_equal(td_rainflow_add(rf, astm[i], take, &t, NULL), TD_OK);
    td_rainflow_residue(rf, take, &t);
    assert_memory_equal(t.count, want, sizeof want);
    td_rainflow_free(&rf);
}

/* The gate: wiggles of 0.4 on the example's history are no reversals with a gate of 0.5, and each
 * adds a cycle of range 0.4 (rounded here to 0) without it; the gate must be finite and >= 0. */
static void test_hysteresis_gate(void **state)
{
    static const double noisy[] = {-2, 1, 0.6, 1, -3, -2.6, -3, 5, -1, 3, 2.6, 3, -4, 4, -2};
    const double want[16] = {[3] = 0.5, [4] = 1.5, [6] = 0.5, [8] = 1.0, [9] = 0.5};
    tally t;
    (void)state;
    count_history(noisy, 15, 0.5, &t);
    assert_memory_equal(t.count, want, sizeof want);
    count_history(noisy, 15, 0.0, &t);
    assert_close(t.count[0], 3.0, 0.0, 0.0); /* three wiggles, three full cycles of 0.4 */
    assert_null(td_rainflow_create(-1.0, NULL));
    assert_null(td_rainflow_create(NAN, NULL));
}

/* A history that never turns back by more than the gate has no cycle; a non-finite value is
 * refused and leaves the counter as it was. */
static void test_flat_and_refused(void **state)
{
    static const double flat[] = {0, 0, 0.2, 0.1, 0.3, 0.2};
    td_error err;
    tally t;
    td_rainflow *rf = td_rainflow_create(0.5, NULL);
    (void)state;
    count_history(flat, 6, 0.5, &t);
    assert_int_equal(t.calls, 0);
    assert_int_equal(td_rainflow_add(rf, 1.0, NULL, NULL, NULL), TD_OK);
    assert_int_equal(td_rainflow_add(rf, NAN, NULL, NULL, &err), TD_ERR_INVALID);
    assert_int_equal(td_rainflow_values(rf), 1);
    td_rainflow_free(&rf);
    td_rainflow_free(&rf);
}

/* A stack that keeps growing (ranges shrinking towards the middle: nothing closes) until the end,
 * which counts it as half cycles: 2000 reversals, past the first capacity many times. */
static void test_long_residue(void **state)
{
    td_rainflow *rf = td_rainflow_create(0.0, NULL);
    tally t;
    int i;
    (void)state;
    memset(&t, 0, sizeof t);
    for (i = 0; i < 2000; i++)
        assert_int_equal(td_rainflow_add(rf, (i % 2 ? -1.0 : 1.0) * (3000 - i) * 1e-3, take, &t, NULL), TD_OK);
    assert_int_equal(t.calls, 0);
    td_rainflow_residue(rf, take, &t);
    assert_int_equal(t.calls, 1999);
    assert_close(t.cycles, 999.5, 0.0, 0.0);
    td_rainflow_free(&rf);
}

/* The damage law by hand. The contact load 0, 1000, 200, 800, 0 N: at its end the rule closes
 * 200-800 (range 600) as a full cycle (the last 0 read as a reversal: X = 800 >= Y = 600), then
 * 0-1000 as a half cycle (it holds the start), and the residue is 1000-0, a half cycle: 2 cycles, damage with C = 10
 * kN, p = 3: 1e-6 (0.06^3 + 0.5 0.1^3 + 0.5 0.1^3) = 1.216e-9. Rolling: 500 N on a race at 10 rev/s for 2 s, 20
 * revolutions of (0.05)^3 1e-6: 2.5e-9. */
static void test_damage_by_hand(void **state)
{
    static const double load[] = {0, 1000, 200, 800, 0};
    const td_life_law law = {10000.0, 3.0}, roller = {10000.0, 10.0 / 3.0}, bad = {0.0, 3.0};
    td_rainflow *rf = td_rainflow_create(TD_LIFE_GATE * law.dynamic_rating / 100.0, NULL);
    tally closed, residue;
    int i;
    (void)state;
    memset(&closed, 0, sizeof closed);
    memset(&residue, 0, sizeof residue);
    for (i = 0; i < 5; i++)
        assert_int_equal(td_rainflow_add(rf, load[i] / 100.0, take, &closed, NULL), TD_OK);
    td_rainflow_residue(rf, take, &residue);
    td_rainflow_free(&rf);
    /* in hundreds of N: nothing closes while the history runs (its last 0 is no reversal until the
     * history turns back from it); its end closes 6 (full) and 10 (half), and the residue is 10 */
    assert_int_equal(closed.calls, 0);
    assert_close(residue.count[6], 1.0, 0.0, 0.0);
    assert_close(residue.count[10], 1.0, 0.0, 0.0);
    assert_close(residue.cycles, 2.0, 0.0, 0.0);
    /* their damage: sum of count (100 range / C)^3 1e-6 */
    assert_close(residue.weighted * 1e6 / 1e12 * 1e-6, 1.216e-9, 1e-14, 0.0);
    assert_close(td_life_cycle_damage(&law, 600.0, 1.0) + 2.0 * td_life_cycle_damage(&law, 1000.0, 0.5), 1.216e-9,
                 1e-14, 0.0);
    assert_close(td_life_rolling_rate(&law, 500.0, 2.0 * TD_PI * 10.0) * 2.0, 2.5e-9, 1e-14, 0.0);
    assert_close(td_life_rolling_rate(&law, 500.0, -2.0 * TD_PI * 10.0) * 2.0, 2.5e-9, 1e-14, 0.0);
    assert_true(td_life_rolling_rate(&law, -5.0, 100.0) == 0.0);
    assert_close(td_life_cycle_damage(&roller, 1000.0, 1.0), pow(0.1, 10.0 / 3.0) * 1e-6, 1e-14, 0.0);
    assert_true(td_is_undefined(td_life_cycle_damage(&bad, 1000.0, 1.0)));
    assert_true(td_is_undefined(td_life_cycle_damage(NULL, 1000.0, 1.0)));
    assert_true(td_is_undefined(td_life_cycle_damage(&law, -1.0, 1.0)));
    assert_true(td_is_undefined(td_life_rolling_rate(&bad, 500.0, 1.0)));
}

/* cases/drop.cfg with its 6011's ratings on both retainers (as shipped, without the ball set). */
static const char *rated[] = {"retainers[0].bearing = { dynamic_rating = 30700.0; static_rating = 21200.0; }",
                              "retainers[1].bearing = { dynamic_rating = 30700.0; static_rating = 21200.0; }"};

/* The drop stepped to t_end on outputs every dt; with `reach`, at every output inside an integrator
 * step (a step's end held beyond it) a second output right at that step's end. Each retainer's
 * totals at t_end into out[2]; returns the outputs at which the held point, once reached, was
 * taken by the counter as one more value (the count grows by 1 there, not before). */
static int drop_life(double dt, double t_end, int reach, td_retainer_totals out[2])
{
    td_case *c = td_test_load_case("cases/drop.cfg", rated, 2);
    td_sim *s = NULL;
    td_error err;
    int k, i, taken = 0;
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, &err), TD_OK);
    for (k = 1; k * dt <= t_end + 1e-12; k++) {
        td_status r;
        while ((r = td_sim_step(s, fmin(k * dt, t_end), NULL, &err)) == TD_EVENT)
            continue;
        assert_int_equal(r, TD_OK);
        if (reach && s->monitor.ahead && s->monitor.ahead_t < (k + 1) * dt && s->monitor.ahead_t < t_end) {
            long before = td_rainflow_values(s->monitor.totals[0].cycles);
            assert_int_equal(td_sim_step(s, s->monitor.ahead_t, NULL, &err), TD_OK);
            taken += td_rainflow_values(s->monitor.totals[0].cycles) == before + 1;
        }
    }
    for (i = 0; i < 2; i++)
        assert_int_equal(td_sim_retainer_totals(s, i, &out[i]), TD_OK);
    td_sim_free(&s);
    td_case_free(&c);
    return taken;
}

/* The counter takes the contact load at the points the run has reached, each once: the same load
 * cycles and damage on output grids of 0.1 ms, 0.37 ms and none (one step to the end), and with
 * extra outputs at the integrator's steps; a step's end held beyond an output is taken only when
 * the run reaches it (the count grows there), never at the output before it. Through the fall and
 * the first bounces of the drop (to 0.111 s, a multiple of both grids). */
static void test_life_independent_of_outputs(void **state)
{
    td_retainer_totals a[2], b[2], c[2], d[2];
    int i, taken;
    (void)state;
    drop_life(1e-4, 0.111, 0, a);
    drop_life(3.7e-4, 0.111, 0, b);
    drop_life(0.111, 0.111, 0, c);
    taken = drop_life(3.7e-4, 0.111, 1, d);
    for (i = 0; i < 2; i++) {
        print_message("retainer %d to 0.111 s: %.6g load cycles, damage %.17g (0.37 ms: %.17g, one step: %.17g, "
                      "reaching the held points: %.17g)\n",
                      i, a[i].load_cycles, a[i].damage, b[i].damage, c[i].damage, d[i].damage);
        assert_true(a[i].load_cycles >= 10.0 && a[i].damage > 0.0);
        assert_true(a[i].load_cycles == b[i].load_cycles && a[i].load_cycles == c[i].load_cycles);
        assert_true(a[i].load_cycles == d[i].load_cycles);
        assert_close(b[i].damage, a[i].damage, 1e-12, 0.0);
        assert_close(c[i].damage, a[i].damage, 1e-12, 0.0);
        assert_close(d[i].damage, a[i].damage, 1e-12, 0.0);
    }
    print_message("%d held points taken when reached\n", taken);
    assert_true(taken > 10);
}

/* No rating, no life: the damage and load cycles are undefined, never 0. Retainer 1's bearing (drop.cfg
 * gives both a 6011) keeps its static rating but loses its dynamic one. */
static const char *one_rated[] = {"retainers[0].bearing = { dynamic_rating = 30700.0; static_rating = 21200.0; }",
                                  "retainers[1].bearing = { static_rating = 21200.0; }"};

static void test_no_rating_no_life(void **state)
{
    td_case *c = td_test_load_case("cases/drop.cfg", one_rated, 2);
    td_sim *s = NULL;
    td_retainer_totals t[2];
    (void)state;
    assert_int_equal(td_sim_create(td_case_model(c), td_case_sim_options(c), &s, NULL), TD_OK);
    while (td_sim_step(s, 0.08, NULL, NULL) == TD_EVENT)
        continue;
    assert_int_equal(td_sim_retainer_totals(s, 0, &t[0]), TD_OK);
    assert_int_equal(td_sim_retainer_totals(s, 1, &t[1]), TD_OK);
    assert_true(t[0].damage > 0.0 && t[0].load_cycles > 0.0);
    assert_true(td_is_undefined(t[1].damage) && td_is_undefined(t[1].load_cycles));
    assert_true(td_is_undefined(td_life_runs_to_failure(t[1].damage)));
    assert_close(td_life_runs_to_failure(t[0].damage), 1.0 / t[0].damage, 0.0, 0.0);
    /* no damage: unlimited (+inf), told apart from no rating (NaN), never 0 */
    assert_true(isinf(td_life_runs_to_failure(0.0)) && td_life_runs_to_failure(0.0) > 0.0);
    assert_true(td_is_undefined(td_life_runs_to_failure(-1.0)));
    td_sim_free(&s);
    td_case_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_astm_worked_example), cmocka_unit_test(test_hysteresis_gate),
        cmocka_unit_test(test_flat_and_refused),    cmocka_unit_test(test_long_residue),
        cmocka_unit_test(test_damage_by_hand),      cmocka_unit_test(test_life_independent_of_outputs),
        cmocka_unit_test(test_no_rating_no_life),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
