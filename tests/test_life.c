/* The touchdown bearing's life (lib/assess: rainflow.c, life.c): the rainflow count against the
 * worked example of ASTM E1049-85 (its Fig. 6 history and Table 4 counts), the hysteresis gate,
 * and the damage law's arithmetic by hand on a short history. The count against an independent
 * implementation (the PyPI package rainflow) is tests/life/rainflow_reference.py. */
#include "td_test.h"

#include "touchdown/assess.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_astm_worked_example), cmocka_unit_test(test_hysteresis_gate),
        cmocka_unit_test(test_flat_and_refused),    cmocka_unit_test(test_long_residue),
        cmocka_unit_test(test_damage_by_hand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
