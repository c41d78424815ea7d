/*
 * td_sweep: the grid of points (ranges with exact ends, log ranges against their closed form,
 * lists with quoted commas, zipped keys, the first axis slowest, the bounds and the errors), the
 * case file's `sweep` group (its specs, its errors at the setting, the command line replacing an
 * axis) and the table writers (the CSV read back; the HDF5 columns and the completeness flag read
 * back with the HDF5 C API).
 */
#include "td_test.h"

#include "touchdown/case.h"
#include "touchdown/sweep.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static td_sweep_grid *grid_of(const char *const *specs, int n)
{
    td_sweep_grid *g = NULL;
    td_error err;
    int i;
    assert_int_equal(td_sweep_grid_create(&g, &err), TD_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(td_sweep_grid_vary(g, specs[i], &err), TD_OK);
    return g;
}

static void test_range_ends_exact(void **state)
{
    const char *specs[] = {"speed=0.1:0.7:7"};
    td_sweep_grid *g = grid_of(specs, 1);
    long p;
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 7);
    assert_true(td_sweep_grid_numeric(g, 0));
    assert_string_equal(td_sweep_grid_value(g, 0, 0), "0.1"); /* the fewest digits that read back */
    /* the last point is STOP itself, not START plus six rounded steps */
    assert_true(strtod(td_sweep_grid_value(g, 6, 0), NULL) == 0.7);
    for (p = 0; p < 7; p++) /* every value reads back to the point's double */
        assert_true(strtod(td_sweep_grid_value(g, p, 0), NULL) == 0.1 + (0.7 - 0.1) * (double)p / 6.0 || p == 6);
    td_sweep_grid_free(&g);
    assert_null(g);
}

static void test_grid_order_and_lists(void **state)
{
    const char *specs[] = {"speed=60:90:2", "contact.model=\"penalty\",constraint", "output.nodes=[1, 2],[3]"};
    td_sweep_grid *g = grid_of(specs, 3);
    char buf[128];
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 8);
    assert_int_equal(td_sweep_grid_axes(g), 3);
    assert_false(td_sweep_grid_numeric(g, 1));
    /* point 5 = speed 1, model 0, nodes 1: the first axis varies slowest */
    assert_string_equal(td_sweep_grid_value(g, 5, 0), "90");
    assert_string_equal(td_sweep_grid_value(g, 5, 1), "\"penalty\"");
    assert_string_equal(td_sweep_grid_value(g, 5, 2), "[3]");
    assert_string_equal(td_sweep_grid_value(g, 0, 2), "[1, 2]");
    td_sweep_grid_override(g, 3, 1, buf, sizeof buf);
    assert_string_equal(buf, "contact.model=constraint");
    assert_string_equal(td_sweep_grid_key(g, 2), "output.nodes");
    assert_string_equal(td_sweep_grid_spec(g, 0), "speed=60:90:2");
    td_sweep_grid_free(&g);
}

/* Every spec of bad[] is refused with a parse error naming it, the grid unchanged. */
static void refuse_all(td_sweep_grid *g, const char *const *bad, size_t n)
{
    td_error err;
    size_t i;
    for (i = 0; i < n; i++) {
        assert_int_equal(td_sweep_grid_vary(g, bad[i], &err), TD_ERR_PARSE);
        assert_non_null(strstr(err.message, bad[i]));
    }
}

static void test_bad_specs(void **state)
{
    static const char *const bad[] = {"speed",         "speed=",          "=1,2",          "speed=1:2",
                                      "speed=1:2:0",   "speed=a:2:3",     "speed=1:2:3:4", "speed=1,,2",
                                      "speed=1:2:1.5", "speed=1:2:100001"};
    td_sweep_grid *g = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    refuse_all(g, bad, sizeof bad / sizeof bad[0]);
    assert_int_equal(td_sweep_grid_axes(g), 0);
    assert_int_equal(td_sweep_grid_vary(g, "speed=1:2:1000", &err), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "speed=3", &err), TD_ERR_PARSE);          /* twice */
    assert_int_equal(td_sweep_grid_vary(g, "end_time=1:2:101", &err), TD_ERR_PARSE); /* 101,000 points */
    assert_non_null(strstr(err.message, "101000 points"));
    assert_int_equal(td_sweep_grid_points(g), 1000);
    td_sweep_grid_free(&g);
    td_sweep_grid_free(&g); /* NULL accepted */
}

/* A spec holding control characters (a pasted ESC, a CR, a newline inside quotes) is refused with
 * one line that shows them escaped: the error is what the tool prints on a terminal. Found by the
 * fuzz target fuzz/fuzz_vary.c. */
static void test_bad_spec_control_chars(void **state)
{
    static const char *const bad[] = {"sp\x1b[2Jeed", "speed=1:2:3\r", "speed=1:2:3:lo\ng", "speed=1,\"a\nb\",,2",
                                      "\x01=1,,2"};
    td_sweep_grid *g = NULL;
    td_error err;
    size_t i;
    const char *p;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(td_sweep_grid_vary(g, bad[i], &err), TD_ERR_PARSE);
        for (p = err.message; *p; p++)
            if ((unsigned char)*p < 0x20)
                fail_msg("spec %zu: a control character 0x%02x in \"%s\"", i, (unsigned)(unsigned char)*p, err.message);
        assert_int_equal(td_sweep_grid_with(g, bad[i], &err), TD_ERR_PARSE);
    }
    assert_int_equal(td_sweep_grid_vary(g, bad[0], &err), TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "--vary 'sp\\x1b[2Jeed'"));
    td_sweep_grid_free(&g);
}

/* 1e-3 to 10 in 9 points: 10^(i/2 - 3), a constant ratio sqrt(10), both ends exact. */
static void test_log_range(void **state)
{
    const char *specs[] = {"x=1e-3:10:9:log"};
    td_sweep_grid *g = grid_of(specs, 1);
    double v[9];
    long p;
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 9);
    assert_true(td_sweep_grid_numeric(g, 0));
    assert_string_equal(td_sweep_grid_value(g, 0, 0), "0.001");
    assert_string_equal(td_sweep_grid_value(g, 8, 0), "10");
    for (p = 0; p < 9; p++) {
        v[p] = strtod(td_sweep_grid_value(g, p, 0), NULL);
        assert_close(v[p], pow(10.0, 0.5 * (double)p - 3.0), 1e-14, 0.0);
    }
    for (p = 1; p < 9; p++)
        assert_close(v[p] / v[p - 1], sqrt(10.0), 1e-14, 0.0);
    td_sweep_grid_free(&g);
}

/* ":linear" is the default spacing; a log range of one point is its start; descending works. */
static void test_log_range_forms(void **state)
{
    const char *specs[] = {"a=1:3:3:linear", "b=7:7e6:1:log", "c=100:1:3:log"};
    td_sweep_grid *g = grid_of(specs, 3);
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 9);
    assert_string_equal(td_sweep_grid_value(g, 3, 0), "2");
    assert_string_equal(td_sweep_grid_value(g, 0, 1), "7");
    assert_string_equal(td_sweep_grid_value(g, 1, 2), "10");
    assert_string_equal(td_sweep_grid_value(g, 2, 2), "1");
    td_sweep_grid_free(&g);
}

static void test_bad_log_ranges(void **state)
{
    static const char *const bad[] = {"x=0:1:3:log", "x=1:-2:3:log", "x=1:2:3:lg", "x=1:2:3:log:4", "x=1:2:3:"};
    td_sweep_grid *g = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    refuse_all(g, bad, sizeof bad / sizeof bad[0]);
    assert_int_equal(td_sweep_grid_vary(g, bad[0], &err), TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "both ends > 0"));
    assert_int_equal(td_sweep_grid_keys(g), 0);
    td_sweep_grid_free(&g);
}

/* Ranges at the edge of a double: whose STOP/START (log) or STOP-START (linear) a double holds give
 * finite points (the geometric mean of 1e-150 and 1e150 is 1, the midpoint of -8e307 and 8e307 is
 * 0); beyond it they are refused naming the ends written, never with a point of inf or 0. */
static void test_range_overflow(void **state)
{
    static const char *const bad[] = {"x=1e-300:1e300:3:log", "x=1e300:1e-300:3:log", "x=1e-320:1:4:log",
                                      "x=-1e308:1e308:5", "x=1.7e308:-1.7e308:3:linear"};
    const char *specs[] = {"a=1e-150:1e150:3:log", "b=-8e307:8e307:3", "c=1e-300:1e300:2:log"};
    td_sweep_grid *g = grid_of(specs, 3);
    td_error err;
    long p;
    size_t i;
    (void)state;
    assert_close(strtod(td_sweep_grid_value(g, 6, 0), NULL), 1.0, 1e-14, 0.0); /* a slowest: 6 points a value */
    assert_close(strtod(td_sweep_grid_value(g, 2, 1), NULL), 0.0, 0.0, 1e293);
    for (p = 0; p < td_sweep_grid_points(g); p++)
        for (i = 0; i < 3; i++)
            assert_true(isfinite(strtod(td_sweep_grid_value(g, p, (int)i), NULL)));
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char ends[64];
        const char *body = strchr(bad[i], '=') + 1, *colon = strchr(body, ':');
        snprintf(ends, sizeof ends, "from %.*s to %.*s", (int)(colon - body), body, (int)strcspn(colon + 1, ":"),
                 colon + 1);
        assert_int_equal(td_sweep_grid_vary(g, bad[i], &err), TD_ERR_PARSE);
        assert_non_null(strstr(err.message, ends));
        assert_null(strstr(err.message, "inf"));
    }
    assert_int_equal(td_sweep_grid_keys(g), 3);
    td_sweep_grid_free(&g);
}

/* a and b zipped (3 values each) times c (2): 6 points, b following a value for value. */
static void test_zip(void **state)
{
    td_sweep_grid *g = NULL;
    td_error err;
    long p;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_with(g, "b=1,2", &err), TD_ERR_PARSE); /* nothing to join */
    assert_int_equal(td_sweep_grid_vary(g, "a=1:3:3", &err), TD_OK);
    assert_int_equal(td_sweep_grid_with(g, "b=10,20,30", &err), TD_OK);
    assert_int_equal(td_sweep_grid_with(g, "d=1,2", &err), TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "--with 'd=1,2': d has 2 values but a, whose axis it joins, has 3"));
    assert_int_equal(td_sweep_grid_with(g, "a=1,2,3", &err), TD_ERR_PARSE); /* swept twice */
    assert_int_equal(td_sweep_grid_vary(g, "c=x,y", &err), TD_OK);
    assert_int_equal(td_sweep_grid_points(g), 6);
    assert_int_equal(td_sweep_grid_axes(g), 2);
    assert_int_equal(td_sweep_grid_keys(g), 3);
    assert_int_equal(td_sweep_grid_axis(g, 1), 0);
    assert_int_equal(td_sweep_grid_axis(g, 2), 1);
    assert_string_equal(td_sweep_grid_origin(g, 1), "command line");
    for (p = 0; p < 6; p++) {
        assert_true(strtod(td_sweep_grid_value(g, p, 1), NULL) == 10.0 * strtod(td_sweep_grid_value(g, p, 0), NULL));
        assert_string_equal(td_sweep_grid_value(g, p, 2), p % 2 ? "y" : "x");
    }
    td_sweep_grid_free(&g);
}

/* At most TD_SWEEP_MAX_KEYS keys in all, zipped ones included. */
static void test_key_limit(void **state)
{
    td_sweep_grid *g = NULL;
    td_error err;
    char spec[32];
    int i;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "k0=1,2", &err), TD_OK);
    for (i = 1; i < TD_SWEEP_MAX_KEYS; i++) {
        snprintf(spec, sizeof spec, "k%d=1,2", i);
        assert_int_equal(td_sweep_grid_with(g, spec, &err), TD_OK);
    }
    assert_int_equal(td_sweep_grid_with(g, "last=1,2", &err), TD_ERR_PARSE);
    assert_non_null(strstr(err.message, "at most 16 swept keys"));
    assert_int_equal(td_sweep_grid_points(g), 2);
    td_sweep_grid_free(&g);
}

static td_case *load_case(const char *path, const char *const *ov, int n, td_error *err)
{
    td_case *c = NULL;
    td_status st = td_case_load(path, ov, n, &c, err);
    if (st != TD_OK) {
        print_error("%s\n", err->message);
        fail();
    }
    return c;
}

/* tests/data/case/all-keys.cfg: speed (log, 3) x magnitude with phase zipped (2). */
static void test_case_group(void **state)
{
    td_case *c;
    td_sweep_grid *g = NULL;
    td_error err;
    const char *where;
    int with;
    (void)state;
    c = load_case(td_source_path("tests/data/case/all-keys.cfg"), NULL, 0, &err);
    assert_int_equal(td_case_sweep_specs(c), 3);
    assert_string_equal(td_case_sweep_spec(c, 0, &with, &where), "speed=10:100:3:log");
    assert_int_equal(with, 0);
    assert_non_null(strstr(where, "all-keys.cfg:"));
    assert_non_null(strstr(where, ": sweep.vary[0]"));
    assert_string_equal(td_case_sweep_spec(c, 1, &with, NULL), "unbalances[0].magnitude=0.001,0.002");
    assert_string_equal(td_case_sweep_spec(c, 2, &with, &where), "unbalances[0].phase=0,1");
    assert_int_equal(with, 1);
    assert_non_null(strstr(where, ": sweep.vary[1].with[0]"));
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_from_case(g, c, &err), TD_OK);
    assert_int_equal(td_sweep_grid_points(g), 6);
    assert_close(strtod(td_sweep_grid_value(g, 2, 0), NULL), pow(10.0, 1.5), 1e-15, 0.0);
    assert_string_equal(td_sweep_grid_value(g, 5, 2), "1");
    assert_non_null(strstr(td_sweep_grid_origin(g, 2), ": sweep.vary[1]"));
    td_sweep_grid_free(&g);
    /* the command line sweeps the phase: the file's whole magnitude-and-phase axis goes */
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "unbalances[0].phase=0.5", &err), TD_OK);
    assert_int_equal(td_sweep_grid_from_case(g, c, &err), TD_OK);
    assert_int_equal(td_sweep_grid_keys(g), 2);
    assert_string_equal(td_sweep_grid_key(g, 1), "speed");
    assert_int_equal(td_sweep_grid_points(g), 3);
    td_sweep_grid_free(&g);
    td_case_free(&c);
}

/* all-keys.cfg's text with its sweep group replaced by `group` at line *line. */
static const char *case_with_group(const char *group, int *line)
{
    static char path[1024];
    td_case *c;
    td_error err;
    const char *text, *cut;
    const char *p;
    FILE *f;
    c = load_case(td_source_path("tests/data/case/all-keys.cfg"), NULL, 0, &err);
    text = td_case_text(c);
    cut = strstr(text, "\nsweep = {");
    assert_non_null(cut);
    *line = 2;
    for (p = text; p < cut; p++)
        *line += *p == '\n';
    mkdir(TD_BINARY_DIR "/tests", 0755);
    snprintf(path, sizeof path, "%s/tests/sweep-group.cfg", TD_BINARY_DIR);
    assert_non_null(f = fopen(path, "w"));
    fprintf(f, "%.*s\n%s\n", (int)(cut - text), text, group);
    fclose(f);
    td_case_free(&c);
    return path;
}

/* A bad group is one error at FILE:LINE and the setting at fault: its shape from td_case_load
 * (judge 0), what its specs mean from td_sweep_check_case (judge 1), which td_case_load leaves to
 * it; td_sweep_grid_from_case gives the same error and leaves the grid as it was. */
static void test_case_group_errors(void **state)
{
    static const struct {
        const char *group, *key, *why;
        int judge;
    } bad[] = {
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; to = 2.0; points = 0; } ); };", "sweep.vary[0].points",
         "whole number from 1 to 100000", 1},
        {"sweep = { vary = ( { key = \"speed\"; from = 0.0; to = 2.0; points = 3; spacing = \"log\"; } ); };",
         "sweep.vary[0].from", "both ends > 0", 1},
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; to = 2.0; points = 3; spacing = \"cubic\"; } ); };",
         "sweep.vary[0].spacing", "linear or log", 1},
        {"sweep = { vary = ( { key = \"speed\"; values = [1.0, 2.0];\n with = ( { key = \"end_time\"; values = [1.0]; "
         "} ); } ); };",
         "sweep.vary[0].with[0].values", "end_time has 1 values but speed", 1},
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; to = 2.0; points = 2;\n with = ( { key = \"end_time\"; "
         "from = 1.0; to = 2.0; points = 3; } ); } ); };",
         "sweep.vary[0].with[0].points", "end_time has 3 values but speed", 1},
        {"sweep = { vary = ( { key = \"speed\"; values = [1.0]; }, { key = \"speed\"; values = [2.0]; } ); };",
         "sweep.vary[1].key", "speed is swept twice", 1},
        {"sweep = { vary = ( { key = \"speed\"; values = [1.0]; points = 2; } ); };", "sweep.vary[0]",
         "either values or a range", 0},
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; points = 2; } ); };", "sweep.vary[0].to", "missing", 0},
        {"sweep = { vary = ( { values = [1.0]; } ); };", "sweep.vary[0].key", "missing", 0},
        {"sweep = { vary = ( { key = \"speed\"; values = [1.0]; step = 2; } ); };", "sweep.vary[0].step", "unknown", 0},
        {"sweep = { vary = ( { key = \"speed\"; values = [ ]; } ); };", "sweep.vary[0].values", "no values", 0},
        /* the reader's order: the key, the values, the range, the spec, then the keys zipped on */
        {"sweep = { vary = ( { key = 1; values = [1.0]; } ); };", "sweep.vary[0].key", "expected a string", 0},
        {"sweep = { vary = ( { key = \"speed\"; from = \"a\"; to = 2.0; points = 2; } ); };", "sweep.vary[0].from",
         "expected a number", 0},
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; to = 2.0; points = 2.5; spacing = 1; } ); };",
         "sweep.vary[0].points", "expected a whole number", 0},
        {"sweep = { vary = ( { key = \"speed\"; from = 1.0; to = 2.0; points = 3; spacing = 1; } ); };",
         "sweep.vary[0].spacing", "expected a string", 0},
        {"sweep = { vary = ( { key = \"speed\"; values = (1.0, [2.0]); with = ( { key = \"end_time\"; values = 3; } ); "
         "} ); };",
         "sweep.vary[0].values[1]", "expected a number, true/false", 0},
        {"sweep = { vary = ( { key = \"speed\"; values = [1.0, 2.0];\n with = ( { key = \"end_time\"; values = [1.0, "
         "2.0]; with = ( ); } ); } ); };",
         "sweep.vary[0].with[0].with", "unknown", 0},
    };
    char want[1100];
    size_t i;
    int line;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *path = case_with_group(bad[i].group, &line);
        td_case *c = NULL;
        td_sweep_grid *g = NULL;
        td_error err, from;
        td_status st = td_case_load(path, NULL, 0, &c, &err);
        assert_int_equal(st, bad[i].judge ? TD_OK : TD_ERR_PARSE);
        if (bad[i].judge) {
            assert_int_equal(td_sweep_check_case(c, &err), TD_ERR_PARSE);
            assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
            assert_int_equal(td_sweep_grid_vary(g, "end_time=1,2,3", &from), TD_OK);
            assert_int_equal(td_sweep_grid_from_case(g, c, &from), TD_ERR_PARSE);
            assert_string_equal(from.message, err.message);
            assert_int_equal(td_sweep_grid_keys(g), 1);
            assert_int_equal(td_sweep_grid_points(g), 3);
            td_sweep_grid_free(&g);
            td_case_free(&c);
        }
        snprintf(want, sizeof want, "%s:%d: %s: ", path, line + (strstr(bad[i].key, "with") != NULL), bad[i].key);
        if (strncmp(err.message, want, strlen(want)) != 0 || !strstr(err.message, bad[i].why)) {
            print_error("case %zu: expected \"%s\" and \"%s\" in \"%s\"\n", i, want, bad[i].why, err.message);
            fail();
        }
    }
}

/* A case without a sweep group passes the judge; a NULL case is refused. */
static void test_case_group_none(void **state)
{
    td_error err;
    td_case *c = load_case(td_source_path("cases/paper-a.cfg"), NULL, 0, &err);
    (void)state;
    assert_int_equal(td_case_sweep_specs(c), 0);
    assert_int_equal(td_sweep_check_case(c, &err), TD_OK);
    assert_int_equal(td_sweep_check_case(NULL, &err), TD_ERR_INVALID);
    td_case_free(&c);
}

/* Three rows: one done, one failed, one not run. */
static void three_rows(td_sweep_row rows[3])
{
    td_run_summary s;
    memset(&s, 0, sizeof s);
    s.status = TD_OK;
    s.peak_housing_force = 1234.5678901234567;
    s.contacts = 7;
    s.first_contact_time = 0.1;
    s.returned_to_free_orbit = 1;
    s.stats.peak_amb = -1;
    snprintf(s.ending, sizeof s.ending, "forward rub at 9 Hz, rolling");
    td_sweep_row_from_summary(&rows[0], &s);
    s.status = TD_ERR_SOLVER;
    snprintf(s.message, sizeof s.message, "failed at t = 0.2, \"badly\"");
    td_sweep_row_from_summary(&rows[1], &s);
    td_sweep_row_unknown(&rows[2], TD_SWEEP_NOT_RUN, "not run", NULL);
}

static void test_csv_table(void **state)
{
    const char *specs[] = {"speed=1,2,3"};
    const char *sets[] = {"end_time=0.2"};
    td_sweep_grid *g = grid_of(specs, 1);
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "speed = 1.0;\n", sets, 1, 0, "interrupted: 1 of 3 points not run"};
    char path[] = "sweep-test.csv";
    char *text;
    (void)state;
    three_rows(rows);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_csv(path, &t, NULL), TD_OK);
    text = td_test_read_file(path);
    assert_non_null(strstr(text, "point [-],speed,status,message,peak_housing_force [N],"));
    assert_non_null(strstr(text, "\n0,1,success,,1234.5678901234567,"));
    assert_non_null(strstr(text, ",\"forward rub at 9 Hz, rolling\","));
    assert_non_null(strstr(text, "\n1,2,solver failure,\"failed at t = 0.2, \"\"badly\"\"\",nan,nan,nan,nan,nan,nan,"));
    assert_non_null(strstr(text, "\n2,3,not run,,nan,"));
    assert_non_null(strstr(
        text, "# vary = speed=1,2,3\n# from = command line\n# set = end_time=0.2\n# case_text:\n#| speed = 1.0;\n"));
    assert_non_null(strstr(text, "# incomplete: interrupted: 1 of 3 points not run\n"));
    assert_int_equal(text[strlen(text) - 1], '\n');
    free(text);
    /* a reason of several lines: the flag stays the file's one last line, as a run's CSV has it */
    t.reason = "stopped:\r\nsecond line";
    assert_int_equal(td_sweep_write_csv(path, &t, NULL), TD_OK);
    text = td_test_read_file(path);
    assert_non_null(strstr(text, "\n# incomplete: stopped:  second line\n"));
    assert_string_equal(strstr(text, "# incomplete: "), "# incomplete: stopped:  second line\n");
    free(text);
    remove(path);
    td_sweep_grid_free(&g);
}

static double read_double(hid_t f, const char *name, int i)
{
    double v[8]; /* the tables here have at most 8 points */
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    assert_true(d >= 0);
    assert_true(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(d);
    return v[i];
}

static int read_flag(hid_t f)
{
    int v = -1;
    hid_t a = H5Aopen(f, "complete", H5P_DEFAULT);
    assert_true(a >= 0);
    assert_true(H5Aread(a, H5T_NATIVE_INT, &v) >= 0);
    H5Aclose(a);
    return v;
}

static void test_hdf5_table(void **state)
{
    const char *specs[] = {"speed=1:3:3"};
    td_sweep_grid *g = grid_of(specs, 1);
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "", NULL, 0, 1, NULL};
    const char *path = "sweep-test.h5";
    hid_t f;
    (void)state;
    three_rows(rows);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_hdf5(path, &t, NULL), TD_OK);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_int_equal(read_flag(f), 1);
    assert_true(read_double(f, "vary/speed", 2) == 3.0);
    assert_true(read_double(f, "peak_housing_force", 0) == 1234.5678901234567);
    assert_true(read_double(f, "contacts", 0) == 7.0);
    /* the failed point: no answers, NaN beside its status (touchdown/dofs.h, "Undefined values") */
    assert_true(td_is_undefined(read_double(f, "contacts", 1)));
    assert_true(td_is_undefined(read_double(f, "peak_housing_force", 1)));
    assert_true(isnan(read_double(f, "wall_time", 2)));
    H5Fclose(f);
    remove(path);
    assert_int_equal(access(path, F_OK), -1);
    td_sweep_grid_free(&g);
}

/* The leaps' columns of four points: one that leapt (3 leaps, 0.75 s), one that was not asked to
 * leap (no leap group, or leap.burst = 0: td_run_summary.leap 0, its leaps and leapt_time zero as
 * the run leaves them), and two that failed, asked to leap and not. Only the first has numbers: a
 * point not asked has no leaps as its run's JSON has none (NaN, never 0, which is "asked, and every
 * leap refused"), a failed point no answers. */
static void test_leap_columns(void **state)
{
    const char *specs[] = {"speed=1,2,3,4"};
    td_sweep_grid *g = grid_of(specs, 1);
    td_sweep_row rows[4];
    td_sweep_table t = {NULL, NULL, "", NULL, 0, 1, NULL};
    td_run_summary s;
    char *text, *at;
    hid_t f;
    int p;
    (void)state;
    memset(&s, 0, sizeof s);
    s.status = TD_OK;
    s.stats.peak_amb = -1;
    s.leap = 1;
    s.leaps = 3;
    s.leapt_time = 0.75;
    td_sweep_row_from_summary(&rows[0], &s);
    s.leap = 0;
    s.leaps = 0;
    s.leapt_time = 0.0;
    td_sweep_row_from_summary(&rows[1], &s);
    s.status = TD_ERR_SOLVER;
    td_sweep_row_from_summary(&rows[3], &s);
    s.leap = 1;
    td_sweep_row_from_summary(&rows[2], &s);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_csv("sweep-leap.csv", &t, NULL), TD_OK);
    text = td_test_read_file("sweep-leap.csv");
    assert_non_null(strstr(text, ",leaps [-],leapt_time [s],warnings,wall_time [s]\n"));
    assert_null(strstr(text, "ended_at_rest")); /* no point was asked to end at rest */
    for (p = 0; p < 4; p++) { /* each line ends "LEAPS,LEAPT_TIME,WARNINGS,WALL_TIME": no warnings, 0 s */
        char line[8];
        const char *want = p == 0 ? ",3,0.75,,0\n" : ",nan,nan,,0\n";
        snprintf(line, sizeof line, "\n%d,", p);
        assert_non_null(at = strstr(text, line));
        at = strchr(at + 1, '\n') + 1;
        assert_true(strncmp(at - strlen(want), want, strlen(want)) == 0);
    }
    free(text);
    remove("sweep-leap.csv");
    assert_int_equal(td_sweep_write_hdf5("sweep-leap.h5", &t, NULL), TD_OK);
    f = H5Fopen("sweep-leap.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_true(read_double(f, "leaps", 0) == 3.0 && read_double(f, "leapt_time", 0) == 0.75);
    for (p = 1; p < 4; p++)
        assert_true(td_is_undefined(read_double(f, "leaps", p)) && td_is_undefined(read_double(f, "leapt_time", p)));
    H5Fclose(f);
    remove("sweep-leap.h5");
    td_sweep_grid_free(&g);
}

static int read_int_attribute(hid_t f, const char *object, const char *name)
{
    int v = -1;
    hid_t a = H5Aopen_by_name(f, object, name, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(a >= 0);
    assert_true(H5Aread(a, H5T_NATIVE_INT, &v) >= 0);
    H5Aclose(a);
    return v;
}

/* A zipped key is a column of its own: CSV "# with" under its axis's "# vary", HDF5 /vary/KEY
 * with the axis it shares. */
static void test_zipped_table(void **state)
{
    td_sweep_grid *g = NULL;
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "", NULL, 0, 1, NULL};
    td_error err;
    char *text;
    hid_t f;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "speed=1:3:3", &err), TD_OK);
    assert_int_equal(td_sweep_grid_with(g, "contact.model=penalty,constraint,penalty", &err), TD_OK);
    three_rows(rows);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_csv("sweep-zip.csv", &t, NULL), TD_OK);
    text = td_test_read_file("sweep-zip.csv");
    assert_non_null(strstr(text, "point [-],speed,contact.model,status,"));
    assert_non_null(strstr(text, "\n1,2,constraint,solver failure,"));
    assert_non_null(strstr(text, "# vary = speed=1:3:3\n# with = contact.model=penalty,constraint,penalty\n"
                                 "# from = command line\n"));
    free(text);
    remove("sweep-zip.csv");
    assert_int_equal(td_sweep_write_hdf5("sweep-zip.h5", &t, NULL), TD_OK);
    f = H5Fopen("sweep-zip.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_true(read_double(f, "vary/speed", 1) == 2.0);
    assert_int_equal(read_int_attribute(f, "vary/speed", "axis"), 0);
    assert_int_equal(read_int_attribute(f, "vary/contact.model", "axis"), 0);
    H5Fclose(f);
    remove("sweep-zip.h5");
    td_sweep_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_range_ends_exact),
        cmocka_unit_test(test_grid_order_and_lists),
        cmocka_unit_test(test_bad_specs),
        cmocka_unit_test(test_csv_table),
        cmocka_unit_test(test_hdf5_table),
        cmocka_unit_test(test_log_range),
        cmocka_unit_test(test_log_range_forms),
        cmocka_unit_test(test_bad_log_ranges),
        cmocka_unit_test(test_range_overflow),
        cmocka_unit_test(test_zip),
        cmocka_unit_test(test_key_limit),
        cmocka_unit_test(test_case_group),
        cmocka_unit_test(test_case_group_errors),
        cmocka_unit_test(test_case_group_none),
        cmocka_unit_test(test_zipped_table),
        cmocka_unit_test(test_leap_columns),
        cmocka_unit_test(test_bad_spec_control_chars), /* found by fuzz/fuzz_vary.c */
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
