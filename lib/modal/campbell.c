/*
 * Campbell diagram (modes over a speed grid, branches tracked by the MAC of their mode shapes
 * from one speed to the next, matched by the optimal assignment) and critical speeds
 * (crossings of a whirl branch with the synchronous line omega_d = Omega, refined by the
 * Illinois variant of regula falsi on fresh eigen-solves).
 */
#include "modal/modal_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Modes of one whirl sense at one speed (ascending omega_d, as td_modal stores them). */
typedef struct whirl_list {
    int count;
    td_mode *modes;
} whirl_list;

struct td_campbell {
    int nspeeds;
    int nbranches;
    double *speeds;  /* nspeeds */
    td_mode *points; /* nspeeds x nbranches, speed-major */
    double *mac;     /* nspeeds x nbranches: each point's weakest MAC link from the previous speed */
    /* For td_campbell_critical_speeds: the system, the grid's ends, and at each grid speed the forward
     * and backward vibration modes (2 nspeeds lists) of its solve, kept when that solve is the full
     * dense one (td_modal_solve), the one the crossing search makes there too; else NULL. */
    const td_system *sys;
    double speed_min, speed_max;
    whirl_list *grid;
};

/* Relative width at which a critical-speed bracket counts as converged. */
#define TD_CRITICAL_RTOL 1e-12
/* A converged point must lie this close to the 1x line, else the bracket straddled a branch jump. */
#define TD_CRITICAL_CHECK 1e-7
#define TD_CRITICAL_MAX_ITER 200

static td_status check_options(const td_modal_options *opt, td_error *err)
{
    if (!opt)
        return td_error_set(err, TD_ERR_INVALID, "modal: NULL options");
    if (!isfinite(opt->speed_min) || !isfinite(opt->speed_max) || opt->speed_max < opt->speed_min)
        return td_error_set(err, TD_ERR_INVALID, "modal: speed range must be finite with speed_max >= speed_min");
    if (opt->speed_steps < 2)
        return td_error_set(err, TD_ERR_INVALID, "modal: speed_steps must be >= 2");
    if (opt->mode_count < 1)
        return td_error_set(err, TD_ERR_INVALID, "modal: mode_count must be >= 1");
    return TD_OK;
}

static double grid_speed(const td_modal_options *opt, int k)
{
    if (k == opt->speed_steps - 1)
        return opt->speed_max;
    return opt->speed_min + (opt->speed_max - opt->speed_min) * (double)k / (double)(opt->speed_steps - 1);
}

/* The forward (lists[0]) and backward (lists[1]) vibration modes of m, each ascending, those below
 * m's td_modal_complete_below (all of a full solve). */
static td_status whirl_split(const td_modal *m, whirl_list lists[2], td_error *err)
{
    static const td_whirl senses[2] = {TD_WHIRL_FORWARD, TD_WHIRL_BACKWARD};
    int i, s;
    td_status st = TD_OK;
    for (s = 0; s < 2; s++) {
        lists[s].count = 0;
        lists[s].modes = NULL;
    }
    for (s = 0; s < 2 && st == TD_OK; s++) {
        lists[s].modes = malloc((size_t)(m->n_modes > 0 ? m->n_modes : 1) * sizeof *lists[s].modes);
        if (!lists[s].modes)
            st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory");
        for (i = 0; st == TD_OK && i < m->n_modes; i++)
            if (m->modes[i].whirl == senses[s] && td_mode_is_vibration(&m->modes[i]) &&
                m->modes[i].omega_d < m->complete_below)
                lists[s].modes[lists[s].count++] = m->modes[i];
        if (st == TD_OK && lists[s].count > 0) { /* kept per grid speed: shrink to the count */
            td_mode *fit = realloc(lists[s].modes, (size_t)lists[s].count * sizeof *fit);
            if (fit)
                lists[s].modes = fit;
        }
    }
    return st;
}

void td_campbell_free(td_campbell **c)
{
    if (!c || !*c)
        return;
    free((*c)->speeds);
    free((*c)->points);
    free((*c)->mac);
    if ((*c)->grid) {
        int k;
        for (k = 0; k < 2 * (*c)->nspeeds; k++)
            free((*c)->grid[k].modes);
        free((*c)->grid);
    }
    free(*c);
    *c = NULL;
}

int td_mode_is_vibration(const td_mode *m)
{
    return m && m->zeta < TD_MODAL_OVERDAMPED_ZETA;
}

const char *td_whirl_name(td_whirl w)
{
    switch (w) {
    case TD_WHIRL_FORWARD: return "forward";
    case TD_WHIRL_BACKWARD: return "backward";
    case TD_WHIRL_MIXED: return "mixed";
    }
    return NULL;
}

/* Branch j at one speed is the j-th lowest vibration mode there (overdamped pairs skipped);
 * missing branches are NAN. */
static void fill_branches(const td_modal *m, td_mode *row, int nbranches)
{
    int i, j = 0;
    for (i = 0; i < m->n_modes && j < nbranches; i++)
        if (td_mode_is_vibration(&m->modes[i]))
            row[j++] = m->modes[i];
    for (; j < nbranches; j++) {
        row[j].sigma = row[j].omega_d = row[j].freq_hz = row[j].omega_n = row[j].zeta = row[j].whirl_index = NAN;
        row[j].whirl = TD_WHIRL_MIXED;
    }
}

double td_shape_mac(const double *a, const double *b, int nn)
{
    double re = 0.0, im = 0.0, aa = 0.0, bb = 0.0;
    int c, k;
    for (c = 0; c < 2; c++) { /* the x, then the y components */
        const double *ar = a + 2 * c * nn, *ai = ar + nn, *br = b + 2 * c * nn, *bi = br + nn;
        for (k = 0; k < nn; k++) {
            re += ar[k] * br[k] + ai[k] * bi[k]; /* conj(a) b */
            im += ar[k] * bi[k] - ai[k] * br[k];
            aa += ar[k] * ar[k] + ai[k] * ai[k];
            bb += br[k] * br[k] + bi[k] * bi[k];
        }
    }
    if (!(aa > 0.0 && bb > 0.0))
        return 0.0;
    return fmin(1.0, (re * re + im * im) / (aa * bb));
}

/* The branches being followed from one speed to the next: each branch's last point (mode and shape;
 * has[j] = 0: none yet), the weakest MAC link that carried it since the last grid speed, and the
 * candidates of the latest solve with the match found among them. */
typedef struct tracker {
    int nb, nn;
    int *has;
    td_mode *mode;
    double *shape;   /* nb x 4 nn */
    double *weakest; /* nb */
    double *link;    /* nb: MAC of the latest match (NAN: matched to nothing) */
    int *match;      /* nb: candidate matched, -1: none */
    int *cand;       /* up to 2 nb candidates: indices of vibration modes of the latest solve, ascending */
    int ncand;
    double *cost; /* nb x 2 nb */
    int *rows, *assign;
    char *taken; /* nb */
} tracker;

static void tracker_free(tracker *t)
{
    free(t->has);
    free(t->mode);
    free(t->shape);
    free(t->weakest);
    free(t->link);
    free(t->match);
    free(t->cand);
    free(t->cost);
    free(t->rows);
    free(t->assign);
    free(t->taken);
}

static int tracker_init(tracker *t, int nb, int nn)
{
    size_t b = (size_t)nb;
    t->nb = nb;
    t->nn = nn;
    t->ncand = 0;
    t->has = calloc(b, sizeof *t->has);
    t->mode = calloc(b, sizeof *t->mode);
    t->shape = calloc(b * 4u * (size_t)(nn > 0 ? nn : 1), sizeof *t->shape);
    t->weakest = calloc(b, sizeof *t->weakest);
    t->link = calloc(b, sizeof *t->link);
    t->match = calloc(b, sizeof *t->match);
    t->cand = calloc(2u * b, sizeof *t->cand);
    t->cost = calloc(2u * b * b, sizeof *t->cost);
    t->rows = calloc(b, sizeof *t->rows);
    t->assign = calloc(b, sizeof *t->assign);
    t->taken = calloc(b, 1);
    return t->taken && t->has && t->mode && t->shape && t->weakest && t->link && t->match && t->cand && t->cost &&
           t->rows && t->assign;
}

static const double *mode_shape(const td_modal *m, int i)
{
    return m->shapes + (size_t)i * 4u * (size_t)m->nnodes;
}

/* Branch j follows mode i of m from here on. */
static void tracker_take(tracker *t, int j, const td_modal *m, int i)
{
    t->has[j] = 1;
    t->mode[j] = m->modes[i];
    memcpy(t->shape + (size_t)j * 4u * (size_t)t->nn, mode_shape(m, i), 4u * (size_t)t->nn * sizeof *t->shape);
}

/* Match the followed branches to the lowest 2 nb vibration modes of m by the assignment of largest
 * total MAC (cost 1 - MAC; columns of cost 1 pad the candidates when fewer than the branches, a branch
 * assigned to one matches nothing). *least: the smallest MAC of a match of a branch whose mode lies
 * below the solve's td_modal_complete_below (1 when none). */
static td_status tracker_match(tracker *t, const td_modal *m, double *least, td_error *err)
{
    int i, j, r, nrows = 0, ncols;
    td_status st;
    t->ncand = 0;
    for (i = 0; i < m->n_modes && t->ncand < 2 * t->nb; i++)
        if (td_mode_is_vibration(&m->modes[i]))
            t->cand[t->ncand++] = i;
    for (j = 0; j < t->nb; j++) {
        t->match[j] = -1;
        t->link[j] = NAN;
        if (t->has[j])
            t->rows[nrows++] = j;
    }
    ncols = t->ncand > nrows ? t->ncand : nrows;
    for (r = 0; r < nrows; r++)
        for (i = 0; i < ncols; i++)
            t->cost[(size_t)r * (size_t)ncols + (size_t)i] =
                i < t->ncand ? 1.0 - td_shape_mac(t->shape + (size_t)t->rows[r] * 4u * (size_t)t->nn,
                                                  mode_shape(m, t->cand[i]), t->nn)
                             : 1.0;
    st = td_assign_min_cost(t->cost, nrows, ncols, t->assign, err);
    *least = 1.0;
    for (r = 0; st == TD_OK && r < nrows; r++)
        if (t->assign[r] < t->ncand) {
            j = t->rows[r];
            t->match[j] = t->assign[r];
            t->link[j] = 1.0 - t->cost[(size_t)r * (size_t)ncols + (size_t)t->assign[r]];
            if (t->mode[j].omega_d < m->complete_below) /* above it the mode may just be absent */
                *least = fmin(*least, t->link[j]);
        }
    return st;
}

/* Move every matched branch on to its match, keeping the weakest link. */
static void tracker_accept(tracker *t, const td_modal *m)
{
    int j;
    for (j = 0; j < t->nb; j++)
        if (t->match[j] >= 0) {
            tracker_take(t, j, m, t->cand[t->match[j]]);
            t->weakest[j] = fmin(t->weakest[j], t->link[j]);
        }
}

/* The Campbell row of the grid speed just solved (m, matched): the lowest nb vibration modes, each in
 * the column of the branch that followed it there. A branch whose mode left the lowest nb (or that
 * had none) takes the lowest mode no branch followed in (its MAC the link from its last point). */
static void tracker_row(tracker *t, const td_modal *m, td_mode *row, double *mac)
{
    int j, q, nwin = t->ncand < t->nb ? t->ncand : t->nb, next = 0;
    char *taken = t->taken;
    memset(taken, 0, (size_t)t->nb);
    for (j = 0; j < t->nb; j++)
        if (t->match[j] >= 0 && t->match[j] < nwin) {
            row[j] = t->mode[j];
            mac[j] = t->weakest[j];
            taken[t->match[j]] = 1;
        }
    for (j = 0; j < t->nb; j++) {
        if (t->match[j] >= 0 && t->match[j] < nwin)
            continue;
        while (next < nwin && taken[next])
            next++;
        if (next == nwin) { /* fewer modes than branches here */
            row[j].sigma = row[j].omega_d = row[j].freq_hz = row[j].omega_n = row[j].zeta = row[j].whirl_index = NAN;
            row[j].whirl = TD_WHIRL_MIXED;
            mac[j] = NAN;
            t->has[j] = 0;
            continue;
        }
        q = next++;
        mac[j] =
            t->has[j] ? td_shape_mac(t->shape + (size_t)j * 4u * (size_t)t->nn, mode_shape(m, t->cand[q]), t->nn) : NAN;
        tracker_take(t, j, m, t->cand[q]);
        row[j] = t->mode[j];
    }
    for (j = 0; j < t->nb; j++)
        t->weakest[j] = 1.0;
}
/* Follow the branches from grid speed s0 to s1, ending with the solve at s1 in *at_s1, matched. A
 * step whose weakest match has MAC < TD_CAMPBELL_MAC_REFINE is halved (down to the grid step over
 * 2^TD_CAMPBELL_MAX_HALVINGS, where the match is taken as it is) and the step doubles again after
 * each accepted one: positions count in units of that finest step, so the speeds are exact. Once a
 * weak match was taken at the finest step (modes that stay degenerate, whose shapes any basis of
 * their plane gives), the rest of the interval is one step: an interval costs at most
 * TD_CAMPBELL_MAX_HALVINGS + 2 solves. */
static td_status track_interval(const td_system *sys, tracker *t, double s0, double s1, td_modal **at_s1, td_error *err)
{
    const long units = 1L << TD_CAMPBELL_MAX_HALVINGS;
    long pos = 0, step = units;
    int floor_hit = 0;
    *at_s1 = NULL;
    while (pos < units) {
        long to = pos + step < units ? pos + step : units;
        double speed = to == units ? s1 : s0 + (s1 - s0) * (double)to / (double)units, least;
        td_modal *m = NULL;
        td_status st = td_modal_solve_lowest(sys, speed, t->nb, &m, err);
        if (st == TD_OK)
            st = tracker_match(t, m, &least, err);
        if (st != TD_OK) {
            td_modal_free(&m);
            return st;
        }
        if (least < TD_CAMPBELL_MAC_REFINE && to - pos > 1 && !floor_hit) {
            td_modal_free(&m);
            step = (to - pos) / 2;
            continue;
        }
        tracker_accept(t, m);
        floor_hit = floor_hit || least < TD_CAMPBELL_MAC_REFINE;
        step = floor_hit ? units : 2 * (to - pos); /* after a weak match at the finest step: one more */
        pos = to;
        if (pos == units)
            *at_s1 = m;
        else
            td_modal_free(&m);
    }
    return TD_OK;
}

/* A new diagram; it keeps its grid's whirl lists when its solves are full dense ones (td_modal_lowest
 * of any demand is td_modal_solve there), the same as the crossing search's at the grid speeds. */
static td_campbell *campbell_new(const td_system *sys, const td_modal_options *opt)
{
    td_campbell *c = calloc(1, sizeof *c);
    int dense = td_modal_state_count(sys) <= TD_MODAL_DENSE_MAX_STATES;
    if (!c)
        return NULL;
    c->nspeeds = opt->speed_steps;
    c->nbranches = opt->mode_count;
    c->sys = sys;
    c->speed_min = opt->speed_min;
    c->speed_max = opt->speed_max;
    c->speeds = malloc((size_t)c->nspeeds * sizeof *c->speeds);
    c->points = malloc((size_t)c->nspeeds * (size_t)c->nbranches * sizeof *c->points);
    c->mac = malloc((size_t)c->nspeeds * (size_t)c->nbranches * sizeof *c->mac);
    c->grid = dense ? calloc(2u * (size_t)c->nspeeds, sizeof *c->grid) : NULL;
    if (!c->speeds || !c->points || !c->mac || (dense && !c->grid))
        td_campbell_free(&c);
    return c;
}

/* Row 0: the lowest modes at the first speed, sorted; each branch starts there. */
static void first_row(td_campbell *c, tracker *t, const td_modal *m)
{
    int j, i = 0;
    fill_branches(m, c->points, c->nbranches);
    for (j = 0; j < c->nbranches; j++) {
        c->mac[j] = NAN;
        t->weakest[j] = 1.0;
        while (i < m->n_modes && !td_mode_is_vibration(&m->modes[i]))
            i++;
        if (i < m->n_modes)
            tracker_take(t, j, m, i++);
    }
}

td_status td_campbell_compute(const td_system *sys, const td_modal_options *opt, td_campbell **out, td_error *err)
{
    td_campbell *c;
    tracker t;
    td_status st;
    int k;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_campbell_compute: NULL output pointer");
    *out = NULL;
    if ((st = check_options(opt, err)) != TD_OK)
        return st;
    if (!(c = campbell_new(sys, opt)))
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the Campbell diagram");
    memset(&t, 0, sizeof t);
    for (k = 0; k < c->nspeeds && st == TD_OK; k++) {
        td_modal *m = NULL;
        size_t row = (size_t)k * (size_t)c->nbranches;
        c->speeds[k] = grid_speed(opt, k);
        if (k == 0 && (st = td_modal_solve_lowest(sys, c->speeds[0], c->nbranches, &m, err)) == TD_OK) {
            if (tracker_init(&t, c->nbranches, m->nnodes))
                first_row(c, &t, m);
            else
                st = td_error_set(err, TD_ERR_NOMEM, "modal: out of memory for the Campbell diagram");
        } else if (k > 0 && (st = track_interval(sys, &t, c->speeds[k - 1], c->speeds[k], &m, err)) == TD_OK) {
            tracker_row(&t, m, c->points + row, c->mac + row);
        }
        if (st == TD_OK && c->grid)
            st = whirl_split(m, &c->grid[2 * k], err);
        td_modal_free(&m);
    }
    tracker_free(&t);
    if (st != TD_OK) {
        td_campbell_free(&c);
        return st;
    }
    *out = c;
    return TD_OK;
}

int td_campbell_speed_count(const td_campbell *c)
{
    return c ? c->nspeeds : 0;
}
int td_campbell_branch_count(const td_campbell *c)
{
    return c ? c->nbranches : 0;
}

double td_campbell_speed(const td_campbell *c, int k)
{
    if (!c || k < 0 || k >= c->nspeeds)
        return NAN;
    return c->speeds[k];
}

double td_campbell_mac(const td_campbell *c, int k, int j)
{
    if (!c || k < 0 || k >= c->nspeeds || j < 0 || j >= c->nbranches)
        return NAN;
    return c->mac[(size_t)k * (size_t)c->nbranches + (size_t)j];
}

td_status td_campbell_get(const td_campbell *c, int k, int j, td_mode *out)
{
    if (!c || !out || k < 0 || k >= c->nspeeds || j < 0 || j >= c->nbranches)
        return TD_ERR_INVALID;
    *out = c->points[(size_t)k * (size_t)c->nbranches + (size_t)j];
    return TD_OK;
}

/* ---- critical speeds ---------------------------------------------------------------------- */

/* What the crossing search solves: the system, and the damped frequency up to which every vibration
 * mode is needed (the top of the speed range: a branch crossing the 1x line there lies below it). */
typedef struct crossing_problem {
    const td_system *sys;
    double wmax;
} crossing_problem;

/* The forward (lists[0]) and backward (lists[1]) vibration modes at one speed, from one eigen-solve. */
static td_status whirl_modes(const crossing_problem *cp, double omega, whirl_list lists[2], td_error *err)
{
    td_modal *m = NULL;
    td_status st = td_modal_lowest(cp->sys, omega, 1, cp->wmax, 0, &m, err);
    lists[0].count = lists[1].count = 0;
    lists[0].modes = lists[1].modes = NULL;
    if (st == TD_OK)
        st = whirl_split(m, lists, err);
    td_modal_free(&m);
    return st;
}

static void whirl_lists_free(whirl_list lists[2])
{
    free(lists[0].modes);
    free(lists[1].modes);
    lists[0].modes = lists[1].modes = NULL;
}

/* g(Omega) = omega_d - Omega of branch `branch` of whirl `which`; *ok = 0 if the branch is absent. */
static td_status branch_gap(const crossing_problem *cp, double omega, td_whirl which, int branch, double *g,
                            td_mode *mode, int *ok, td_error *err)
{
    whirl_list l[2];
    const whirl_list *w = &l[which == TD_WHIRL_FORWARD ? 0 : 1];
    td_status st = whirl_modes(cp, omega, l, err);
    if (st != TD_OK)
        return st;
    *ok = branch < w->count;
    if (*ok) {
        *g = w->modes[branch].omega_d - omega;
        if (mode)
            *mode = w->modes[branch];
    }
    whirl_lists_free(l);
    return TD_OK;
}

/* Refine a bracketed crossing [a, b] (ga, gb of opposite signs) by the Illinois method. *found = 0
 * when the branch vanished inside or the limit is a jump between branches, not a crossing. */
static td_status refine(const crossing_problem *cp, td_whirl which, int branch, double a, double ga, double b,
                        double gb, td_critical_speed *cs, int *found, td_error *err)
{
    int side = 0, iter, ok;
    double x = a, gx = ga;
    td_mode mode;
    td_status st;
    *found = 0;
    for (iter = 0; iter < TD_CRITICAL_MAX_ITER; iter++) {
        x = (a * gb - b * ga) / (gb - ga);
        if (!(x > a && x < b))
            x = 0.5 * (a + b);
        st = branch_gap(cp, x, which, branch, &gx, &mode, &ok, err);
        if (st != TD_OK)
            return st;
        if (!ok)
            return TD_OK;
        if (gx == 0.0)
            break;
        if ((gx > 0.0) == (ga > 0.0)) {
            a = x;
            ga = gx;
            if (side == -1)
                gb *= 0.5; /* Illinois: halve the stale end's weight */
            side = -1;
        } else {
            b = x;
            gb = gx;
            if (side == 1)
                ga *= 0.5;
            side = 1;
        }
        if (b - a <= TD_CRITICAL_RTOL * fabs(b))
            break;
    }
    /* x, gx, mode: the last evaluated point, at most one bracket width from the root */
    if (fabs(gx) > TD_CRITICAL_CHECK * fabs(x))
        return TD_OK;
    cs->speed = x;
    cs->freq_hz = x / (2.0 * TD_PI);
    cs->zeta = mode.zeta;
    cs->sigma = mode.sigma;
    cs->whirl = which;
    cs->branch = branch;
    *found = 1;
    return TD_OK;
}

/* A growable result list. */
typedef struct cs_list {
    td_critical_speed *items;
    int count, capacity;
} cs_list;

static td_status cs_push(cs_list *l, const td_critical_speed *c, td_error *err)
{
    if (l->count == l->capacity) {
        int cap = l->capacity ? 2 * l->capacity : 8;
        td_critical_speed *p = realloc(l->items, (size_t)cap * sizeof *p);
        if (!p)
            return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory collecting critical speeds");
        l->items = p;
        l->capacity = cap;
    }
    l->items[l->count++] = *c;
    return TD_OK;
}

static int cmp_speed(const void *a, const void *b)
{
    const td_critical_speed *x = a, *y = b;
    return x->speed < y->speed ? -1 : (x->speed > y->speed ? 1 : 0);
}

/* Scan one grid interval [s0, s1] (whirl lists l0, l1 there) for branch crossings. */
static td_status scan_interval(const crossing_problem *cp, td_whirl which, double s0, const whirl_list *l0, double s1,
                               const whirl_list *l1, cs_list *res, td_error *err)
{
    int j, n = l0->count < l1->count ? l0->count : l1->count;
    for (j = 0; j < n; j++) {
        double g0 = l0->modes[j].omega_d - s0, g1 = l1->modes[j].omega_d - s1;
        td_critical_speed cs;
        int found = 0;
        td_status st;
        if (g0 == 0.0 || g1 == 0.0 || (g0 > 0.0) == (g1 > 0.0))
            continue;
        st = refine(cp, which, j, s0, g0, s1, g1, &cs, &found, err);
        if (st != TD_OK)
            return st;
        if (found && (st = cs_push(res, &cs, err)) != TD_OK)
            return st;
    }
    /* a crossing exactly on the grid point s0 */
    for (j = 0; j < l0->count; j++)
        if (l0->modes[j].omega_d - s0 == 0.0) {
            td_critical_speed cs = {s0, s0 / (2.0 * TD_PI), l0->modes[j].zeta, l0->modes[j].sigma, which, j};
            td_status st = cs_push(res, &cs, err);
            if (st != TD_OK)
                return st;
        }
    return TD_OK;
}

/* A copy of a whirl list (to be freed as whirl_modes' lists are). */
static td_status whirl_copy(const whirl_list *from, whirl_list *to, td_error *err)
{
    to->count = from->count;
    to->modes = malloc((size_t)(from->count > 0 ? from->count : 1) * sizeof *to->modes);
    if (!to->modes)
        return td_error_set(err, TD_ERR_NOMEM, "modal: out of memory");
    memcpy(to->modes, from->modes, (size_t)from->count * sizeof *to->modes);
    return TD_OK;
}

/* The whirl lists at grid speed k: a copy of those of `grid` (the Campbell diagram's, the same solve)
 * when there are any, else from a fresh solve. */
static td_status grid_modes(const crossing_problem *cp, const whirl_list *grid, int k, double sp, whirl_list cur[2],
                            td_error *err)
{
    td_status st;
    if (!grid)
        return whirl_modes(cp, sp, cur, err);
    cur[0].modes = cur[1].modes = NULL;
    st = whirl_copy(&grid[2 * k], &cur[0], err);
    return st == TD_OK ? whirl_copy(&grid[2 * k + 1], &cur[1], err) : st;
}

/* td_modal_critical_speeds, with the grid's whirl lists from `grid` (2 speed_steps lists) if not NULL. */
static td_status critical_speeds(const td_system *sys, const td_modal_options *opt, const whirl_list *grid,
                                 td_critical_speed *out, int capacity, int *count, td_error *err)
{
    static const td_whirl senses[2] = {TD_WHIRL_FORWARD, TD_WHIRL_BACKWARD};
    cs_list res = {NULL, 0, 0};
    td_status st;
    int s, k, i;
    crossing_problem cp;
    whirl_list prev[2] = {{0, NULL}, {0, NULL}}, cur[2];
    double sprev = 0.0;
    if (!count || capacity < 0 || (capacity > 0 && !out))
        return td_error_set(err, TD_ERR_INVALID, "td_modal_critical_speeds: bad output arguments");
    *count = 0;
    st = check_options(opt, err);
    if (st != TD_OK)
        return st;
    cp.sys = sys;
    cp.wmax = opt->speed_max;
    /* one eigen-solve per grid speed serves both whirl senses */
    for (k = 0; k < opt->speed_steps && st == TD_OK; k++) {
        double sp = grid_speed(opt, k);
        st = grid_modes(&cp, grid, k, sp, cur, err);
        for (s = 0; s < 2 && st == TD_OK && k > 0; s++)
            st = scan_interval(&cp, senses[s], sprev, &prev[s], sp, &cur[s], &res, err);
        whirl_lists_free(prev);
        prev[0] = cur[0];
        prev[1] = cur[1];
        sprev = sp;
    }
    whirl_lists_free(prev);
    if (st != TD_OK) {
        free(res.items);
        return st;
    }
    qsort(res.items, (size_t)res.count, sizeof *res.items, cmp_speed);
    for (i = 0; i < res.count && i < capacity; i++)
        out[i] = res.items[i];
    *count = res.count;
    free(res.items);
    return TD_OK;
}

td_status td_modal_critical_speeds(const td_system *sys, const td_modal_options *opt, td_critical_speed *out,
                                   int capacity, int *count, td_error *err)
{
    return critical_speeds(sys, opt, NULL, out, capacity, count, err);
}

td_status td_campbell_critical_speeds(const td_campbell *c, const td_system *sys, const td_modal_options *opt,
                                      td_critical_speed *out, int capacity, int *count, td_error *err)
{
    int same = c && c->grid && opt && c->sys == sys && c->nspeeds == opt->speed_steps &&
               c->speed_min == opt->speed_min && c->speed_max == opt->speed_max;
    return critical_speeds(sys, opt, same ? c->grid : NULL, out, capacity, count, err);
}
