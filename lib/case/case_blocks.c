/*
 * The blocks of a controller's law (case_schema.h, td_cr_read_block): a block is a group with
 * exactly one member, the block's kind, read by the kind's table and made a SISO controller with
 * the controller API (touchdown/controller.h), which holds every rule about the values (a
 * frequency > 0, a notch's depth below 1, a law improper by at most one). The reader checks what
 * is about the file: the one member, the keys, the shapes of the coefficient lists and matrices,
 * and that a block in z has a sample rate.
 */
#include "case/case_schema.h"
#include "touchdown/dofs.h" /* TD_PI */
#include "util/error_internal.h"

#include <math.h>
#include <string.h>

/* The most states of an `ss` block, roots of a `zpk` and coefficients of a `tf` polynomial: an
 * AMB controller's block is a filter of a few states, written by hand. */
#define CB_MAX_ORDER 16
#define CB_MAX_COEFS (CB_MAX_ORDER + 2)

static const char *const domain_names[] = {"s", "z"};

#define CB_STR_(x) #x
#define CB_STR(x) CB_STR_(x)
/* The range of a block's frequency, a rule of the controller API (touchdown/controller.h). */
#define CB_FREQUENCY_RANGE CB_STR(TD_CONTROLLER_FREQUENCY_MIN) " to " CB_STR(TD_CONTROLLER_FREQUENCY_MAX)

/* The kinds of block, in the order of block_keys. */
enum { CB_GAIN, CB_PID, CB_LEADLAG, CB_LOWPASS, CB_NOTCH, CB_RESONANT, CB_TF, CB_ZPK, CB_SS, CB_PARALLEL };

/* A `tf` block. */
typedef struct cb_tf {
    double num[CB_MAX_COEFS], den[CB_MAX_COEFS];
    int n_num, n_den;
    int domain;
} cb_tf;

/* A `zpk` block; a root with im != 0 stands for its conjugate pair. */
typedef struct cb_zpk {
    double zero_re[CB_MAX_ORDER], zero_im[CB_MAX_ORDER], pole_re[CB_MAX_ORDER], pole_im[CB_MAX_ORDER];
    int n_zeros, n_poles;
    double gain;
    int domain;
} cb_zpk;

/* An `ss` block: A, B, C and D as written (rows of entries, row-major), their shapes. */
typedef struct cb_ss {
    double m[4][CB_MAX_ORDER * CB_MAX_ORDER];
    int rows[4], cols[4];
    int domain;
} cb_ss;

/* A block's `domain` key; what the domain says of its numbers is the block's own doc. */
#define DOMAIN(rec, what)                                                                                              \
    {                                                                                                                  \
        .key = "domain", .type = TD_CS_ENUM, .offset = offsetof(rec, domain), .names = domain_names, .name_count = 2,  \
        .doc = what                                                                                                    \
    }

static const td_cs_key pid_keys[] = {
    {.key = "kp", .type = TD_CS_REAL, .offset = offsetof(td_pid_block, kp), .unit = "A/m", .doc = "proportional gain"},
    {.key = "kint",
     .type = TD_CS_REAL,
     .offset = offsetof(td_pid_block, kint),
     .range = TD_CR_NONNEGATIVE,
     .unit = "A/(m s)",
     .doc = "integral gain: kint / s"},
    {.key = "kd",
     .type = TD_CS_REAL,
     .offset = offsetof(td_pid_block, kd),
     .unit = "A s/m",
     .doc = "derivative gain: kd s / (1 + s / (2 pi derivative_filter))"},
    {.key = "derivative_filter",
     .type = TD_CS_REAL,
     .offset = offsetof(td_pid_block, derivative_filter),
     .range = TD_CR_NONNEGATIVE,
     .doc_range = "0, or " CB_FREQUENCY_RANGE,
     .doc_default = "0 (the exact derivative: continuous only)",
     .unit = "Hz",
     .doc = "corner of the derivative's first-order filter; 0: kd s on the exact sensor velocity, as the AMB "
            "shorthand's kd"},
};
static const td_cs_table pid_table = {"controllers[].law[].pid", NULL, pid_keys, TD_CS_COUNT(pid_keys),
                                      sizeof(td_pid_block),      NULL, NULL};

static const td_cs_key leadlag_keys[] = {
    {.key = "gain",
     .type = TD_CS_REAL,
     .offset = offsetof(td_leadlag_block, gain),
     .need = TD_CS_REQUIRED,
     .what = "gain g, A/m as a first block",
     .doc = "g in g (1 + s / (2 pi zero)) / (1 + s / (2 pi pole)); A/m as a first block, dimensionless after one"},
    {.key = "zero",
     .type = TD_CS_REAL,
     .offset = offsetof(td_leadlag_block, zero),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .what = "zero frequency, Hz",
     .unit = "Hz",
     .doc = "the zero's frequency (a lead: zero < pole)"},
    {.key = "pole",
     .type = TD_CS_REAL,
     .offset = offsetof(td_leadlag_block, pole),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .what = "pole frequency, Hz",
     .unit = "Hz",
     .doc = "the pole's frequency"},
};
static const td_cs_table leadlag_table = {"controllers[].law[].leadlag", NULL, leadlag_keys, TD_CS_COUNT(leadlag_keys),
                                          sizeof(td_leadlag_block),      NULL, NULL};

static void lowpass_preset(void *rec)
{
    td_lowpass_block *b = rec;
    b->order = 2;
    b->damping = sqrt(0.5); /* Butterworth */
}

static const td_cs_key lowpass_keys[] = {
    {.key = "frequency",
     .type = TD_CS_REAL,
     .offset = offsetof(td_lowpass_block, frequency),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .what = "corner frequency, Hz",
     .unit = "Hz",
     .doc = "corner frequency fc (wc = 2 pi fc)"},
    {.key = "order",
     .type = TD_CS_INT,
     .offset = offsetof(td_lowpass_block, order),
     .need = TD_CS_PRESET,
     .lo = 1,
     .hi = 2,
     .doc = "1: wc / (s + wc); 2: wc^2 / (s^2 + 2 damping wc s + wc^2)"},
    {.key = "damping",
     .type = TD_CS_REAL,
     .offset = offsetof(td_lowpass_block, damping),
     .need = TD_CS_PRESET,
     .range = TD_CR_POSITIVE,
     .doc_default = "1/sqrt(2) (Butterworth)",
     .doc = "damping ratio of the second-order filter (order 2 only)"},
};
static const td_cs_table lowpass_table = {
    "controllers[].law[].lowpass", NULL,           lowpass_keys, TD_CS_COUNT(lowpass_keys),
    sizeof(td_lowpass_block),      lowpass_preset, NULL};

static const td_cs_key notch_keys[] = {
    {.key = "frequency",
     .type = TD_CS_REAL,
     .offset = offsetof(td_notch_block, frequency),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .what = "notch frequency, Hz",
     .unit = "Hz",
     .doc = "centre frequency fn (wn = 2 pi fn): a bending mode's"},
    {.key = "width",
     .type = TD_CS_REAL,
     .offset = offsetof(td_notch_block, width),
     .need = TD_CS_REQUIRED,
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .what = "-3 dB width, Hz",
     .unit = "Hz",
     .doc = "the -3 dB band: damping of the poles zp = width / (2 fn)"},
    {.key = "depth",
     .type = TD_CS_REAL,
     .offset = offsetof(td_notch_block, depth),
     .range = TD_CR_NONNEGATIVE,
     .doc_range = ">= 0, < 1",
     .doc = "the gain at fn: damping of the zeros zz = depth zp (0: a full notch)"},
};
static const td_cs_table notch_table = {"controllers[].law[].notch", NULL, notch_keys, TD_CS_COUNT(notch_keys),
                                        sizeof(td_notch_block),      NULL, NULL};

/* resonant.frequency absent: the case's speed Omega / (2 pi) (read before the controllers). */
static td_status resonant_frequency(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    td_resonant_block *b = rec;
    double speed = td_model_speed(r->c->model);
    if (td_cr_has(g, k->key))
        return TD_OK;
    b->frequency = speed / (2.0 * TD_PI);
    /* the library's bound, said here in terms of the speed the user wrote, not of a frequency they did not */
    if (!(b->frequency >= TD_CONTROLLER_FREQUENCY_MIN && b->frequency <= TD_CONTROLLER_FREQUENCY_MAX))
        return td_cr_fail(r, g, k->key,
                          "absent, it is the case's speed / (2 pi) = %g Hz (speed %g rad/s), outside %g to %g Hz: "
                          "give the frequency (Hz)",
                          b->frequency, speed, TD_CONTROLLER_FREQUENCY_MIN, TD_CONTROLLER_FREQUENCY_MAX);
    return TD_OK;
}

static const td_cs_key resonant_keys[] = {
    {.key = "gain",
     .type = TD_CS_REAL,
     .offset = offsetof(td_resonant_block, gain),
     .need = TD_CS_REQUIRED,
     .what = "gain g, A/(m s) as a first block",
     .doc = "g in g (s cos phase + w sin phase) / (s^2 + 2 damping w s + w^2); A/(m s) as a first block, 1/s "
            "after one (the fraction is in s)"},
    {.key = "phase",
     .type = TD_CS_REAL,
     .offset = offsetof(td_resonant_block, phase),
     .unit = "degree",
     .doc = "phase: 0 gives g s / (s^2 + 2 damping w s + w^2), 90 gives g w / (...); at w a damped block is "
            "g / (2 damping w) e^(-j phase)"},
    {.key = "frequency",
     .type = TD_CS_REAL,
     .offset = offsetof(td_resonant_block, frequency),
     .range = TD_CR_POSITIVE,
     .doc_range = CB_FREQUENCY_RANGE,
     .check = resonant_frequency,
     .doc_default = "the case's `speed` / (2 pi)",
     .unit = "Hz",
     .doc = "the resonance f (w = 2 pi f), where an undamped block's gain is infinite; absent, the rotor's speed "
            "at t = 0 (a synchronous compensator; it stays there through a `speed_ramp` or a free `spin`)"},
    {.key = "damping",
     .type = TD_CS_REAL,
     .offset = offsetof(td_resonant_block, damping),
     .doc_range = ">= 0, < 1",
     .doc = "damping ratio of the poles: 0 is the undamped internal model of a sinusoid at w, > 0 a damper whose "
            "gain at w is finite, g / (2 damping w)"},
};
static const td_cs_table resonant_table = {
    "controllers[].law[].resonant", NULL, resonant_keys, TD_CS_COUNT(resonant_keys),
    sizeof(td_resonant_block),      NULL, NULL};

static const td_cs_key tf_keys[] = {
    {.key = "num",
     .type = TD_CS_REALS,
     .offset = offsetof(cb_tf, num),
     .count_offset = offsetof(cb_tf, n_num),
     .hi = CB_MAX_COEFS,
     .doc_default = "required",
     .doc = "numerator coefficients (in s: at most one degree above the denominator)"},
    {.key = "den",
     .type = TD_CS_REALS,
     .offset = offsetof(cb_tf, den),
     .count_offset = offsetof(cb_tf, n_den),
     .hi = CB_MAX_COEFS,
     .doc_default = "required",
     .doc = "denominator coefficients (in z^-1: the first nonzero)"},
    DOMAIN(cb_tf, "`\"s\"`: continuous, `num` and `den` in descending powers of s; `\"z\"`: sampled at the "
                  "controller's `sample_rate`, in ascending powers of z^-1"),
};
static const td_cs_table tf_table = {
    "controllers[].law[].tf", NULL, tf_keys, TD_CS_COUNT(tf_keys), sizeof(cb_tf), NULL, NULL};

/* zeros or poles: a list of [re, im] pairs, one per real root or conjugate pair. */
static td_status read_roots(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    cb_zpk *z = rec;
    int is_zeros = strcmp(k->key, "zeros") == 0, i;
    double *re = is_zeros ? z->zero_re : z->pole_re, *im = is_zeros ? z->zero_im : z->pole_im;
    const config_setting_t *s = config_setting_get_member(g, k->key);
    td_status st = TD_OK;
    if (!s)
        return TD_OK;
    if (!config_setting_is_list(s) && !(config_setting_is_array(s) && config_setting_length(s) == 0))
        return td_cr_fail(r, s, NULL, "expected a list of roots ( [re, im], ... )");
    if (config_setting_length(s) > CB_MAX_ORDER)
        return td_cr_fail(r, s, NULL, "too many roots (%d, at most %d)", config_setting_length(s), CB_MAX_ORDER);
    for (i = 0; st == TD_OK && i < config_setting_length(s); i++) {
        const config_setting_t *root = config_setting_get_elem(s, (unsigned)i);
        if (!config_setting_is_array(root) || config_setting_length(root) != 2)
            return td_cr_fail(r, root, NULL, "expected a root [re, im] (im != 0: the root and its conjugate)");
        st = td_cr_value_real(r, config_setting_get_elem(root, 0), TD_CR_FINITE, &re[i]);
        if (st == TD_OK)
            st = td_cr_value_real(r, config_setting_get_elem(root, 1), TD_CR_FINITE, &im[i]);
    }
    *(is_zeros ? &z->n_zeros : &z->n_poles) = i;
    return st;
}

static const td_cs_key zpk_keys[] = {
    {.key = "zeros",
     .type = TD_CS_CUSTOM,
     .read = read_roots,
     .doc_type = "list of [re, im]",
     .doc_default = "none",
     .unit = "rad/s",
     .doc = "the zeros (in z: dimensionless); a root with im != 0 stands for itself and its conjugate"},
    {.key = "poles",
     .type = TD_CS_CUSTOM,
     .read = read_roots,
     .doc_type = "list of [re, im]",
     .doc_default = "none",
     .unit = "rad/s",
     .doc = "the poles, as the zeros"},
    {.key = "gain",
     .type = TD_CS_REAL,
     .offset = offsetof(cb_zpk, gain),
     .def = 1.0,
     .doc = "k in k prod(s - zero) / prod(s - pole)"},
    DOMAIN(cb_zpk, "`\"s\"`: continuous, the zeros and poles in the s-plane (1/s); `\"z\"`: sampled at the "
                   "controller's `sample_rate`, the zeros and poles in the z-plane"),
};
static const td_cs_table zpk_table = {
    "controllers[].law[].zpk", NULL, zpk_keys, TD_CS_COUNT(zpk_keys), sizeof(cb_zpk), NULL, NULL};

/* One row [ ... ] of a matrix into out (at most max entries); *n its length. */
static td_status read_row(td_case_reader *r, const config_setting_t *row, int max, double *out, int *n)
{
    int j;
    td_status st = TD_OK;
    if (!config_setting_is_array(row))
        return td_cr_fail(r, row, NULL, "expected a row [ ... ] of numbers");
    if (config_setting_length(row) > max)
        return td_cr_fail(r, row, NULL, "too many entries (%d, at most %d)", config_setting_length(row), max);
    for (j = 0; st == TD_OK && j < config_setting_length(row); j++)
        st = td_cr_value_real(r, config_setting_get_elem(row, (unsigned)j), TD_CR_FINITE, &out[j]);
    *n = j;
    return st;
}

/* A, B, C or D: a list of rows ( [ ... ], [ ... ] ) of equal length, row-major into the record;
 * an array [ ... ] is one row. Absent: 0 x 0. */
static td_status read_matrix(td_case_reader *r, const config_setting_t *g, const td_cs_key *k, void *rec)
{
    cb_ss *ss = rec;
    int which = k->key[0] - 'A', i, n = 0;
    const config_setting_t *s = config_setting_get_member(g, k->key);
    td_status st = TD_OK;
    ss->rows[which] = ss->cols[which] = 0;
    if (!s)
        return TD_OK;
    if (config_setting_is_array(s) && config_setting_length(s) > 0) {
        ss->rows[which] = 1;
        return read_row(r, s, CB_MAX_ORDER, ss->m[which], &ss->cols[which]);
    }
    if (!config_setting_is_list(s) && !config_setting_is_array(s))
        return td_cr_fail(r, s, NULL, "expected a matrix: a list of rows ( [ ... ], [ ... ] )");
    if (config_setting_length(s) > CB_MAX_ORDER)
        return td_cr_fail(r, s, NULL, "too many rows (%d, at most %d)", config_setting_length(s), CB_MAX_ORDER);
    for (i = 0; st == TD_OK && i < config_setting_length(s); i++) {
        const config_setting_t *row = config_setting_get_elem(s, (unsigned)i);
        st = read_row(r, row, CB_MAX_ORDER, ss->m[which] + i * CB_MAX_ORDER, &n);
        if (st == TD_OK && i > 0 && n != ss->cols[which])
            return td_cr_fail(r, row, NULL, "row %d has %d entries, row 0 has %d", i, n, ss->cols[which]);
        ss->cols[which] = n;
    }
    ss->rows[which] = i;
    return st;
}

static const td_cs_key ss_keys[] = {
    {.key = "A",
     .type = TD_CS_CUSTOM,
     .read = read_matrix,
     .doc_type = "list of rows",
     .doc_default = "none (no state)",
     .doc = "n x n: x' = A x + B e (in z: x[k+1] = A x[k] + B e[k])"},
    {.key = "B",
     .type = TD_CS_CUSTOM,
     .read = read_matrix,
     .doc_type = "list of rows",
     .doc_default = "none (no state)",
     .doc = "n x 1: one row [b] per state"},
    {.key = "C",
     .type = TD_CS_CUSTOM,
     .read = read_matrix,
     .doc_type = "list of rows",
     .doc_default = "none (no state)",
     .doc = "1 x n: i = C x + D e"},
    {.key = "D",
     .type = TD_CS_CUSTOM,
     .read = read_matrix,
     .doc_type = "list of rows",
     .doc_default = "required",
     .doc = "1 x 1, e.g. `([0.0])`; an array `[ ... ]` is one row"},
    DOMAIN(cb_ss, "`\"s\"`: continuous, x' = A x + B e; `\"z\"`: sampled at the controller's `sample_rate`, "
                  "x[k+1] = A x[k] + B e[k]"),
};
static const td_cs_table ss_table = {
    "controllers[].law[].ss", NULL, ss_keys, TD_CS_COUNT(ss_keys), sizeof(cb_ss), NULL, NULL};

#define BLOCK(name, tab, what)                                                                                         \
    {                                                                                                                  \
        .key = name, .type = TD_CS_GROUP, .sub = &tab, .read = td_cs_elsewhere, .doc_default = "-", .doc = what        \
    }

static const td_cs_key block_keys[] = {
    {.key = "gain",
     .type = TD_CS_REAL,
     .read = td_cs_elsewhere,
     .doc_default = "-",
     .doc = "a constant gain k: `{ gain = 2.0; }`"},
    BLOCK("pid", pid_table, "kp + kint / s + kd s / (1 + s / (2 pi derivative_filter)), below"),
    BLOCK("leadlag", leadlag_table, "gain (1 + s / (2 pi zero)) / (1 + s / (2 pi pole)), below"),
    BLOCK("lowpass", lowpass_table, "a first- or second-order low-pass filter, below"),
    BLOCK("notch", notch_table, "(s^2 + 2 zz wn s + wn^2) / (s^2 + 2 zp wn s + wn^2), below"),
    BLOCK("resonant", resonant_table, "gain (s cos phase + w sin phase) / (s^2 + 2 damping w s + w^2), below"),
    BLOCK("tf", tf_table, "a transfer function num / den, below"),
    BLOCK("zpk", zpk_table, "zeros, poles and gain, below"),
    BLOCK("ss", ss_table, "a SISO state-space realisation (A, B, C, D), below"),
    {.key = "parallel",
     .type = TD_CS_CUSTOM,
     .read = td_cs_elsewhere,
     .doc_type = "list of branches",
     .doc_default = "-",
     .doc = "branches fed the same error, their outputs summed: `{ parallel = ( ( { pid = { ... }; }, { notch = { "
            "... }; } ), { resonant = { ... }; } ); }` is pid then notch, plus a resonant; a branch is a block or a "
            "list of blocks in series, every branch all in s or all in z"},
};
const td_cs_table td_cs_block = {"controllers[].law[]", NULL, block_keys, TD_CS_COUNT(block_keys), 0, NULL, NULL};

/* The one member of block e: its kind (the index in block_keys). */
static td_status block_member(td_case_reader *r, const config_setting_t *e, const config_setting_t **member, int *kind)
{
    int i;
    td_status st = td_cs_check_keys(r, e, &td_cs_block);
    if (st != TD_OK)
        return st;
    if (config_setting_length(e) == 0)
        return td_cr_fail(r, e, NULL,
                          "an empty block: a block is a group with one member, gain, pid, leadlag, lowpass, notch, "
                          "resonant, tf, zpk, ss or parallel");
    if (config_setting_length(e) > 1)
        return td_cr_fail(r, config_setting_get_elem(e, 1), NULL,
                          "a block has exactly one member (this one also has '%s'): write each block as a group of "
                          "its own, in series in the list",
                          config_setting_name(config_setting_get_elem(e, 0)));
    *member = config_setting_get_elem(e, 0);
    for (i = 0; i < td_cs_block.count && strcmp(block_keys[i].key, config_setting_name(*member)) != 0; i++)
        ;
    *kind = i;
    if (i == CB_PARALLEL && !(config_setting_is_list(*member) && config_setting_length(*member) > 0))
        return td_cr_fail(r, *member, NULL,
                          "expected a list of branches ( ( { ... }, { ... } ), { ... } ), each a block or a list of "
                          "blocks in series");
    if (i > 0 && i != CB_PARALLEL && !config_setting_is_group(*member))
        return td_cr_fail(r, *member, NULL, "expected a group { ... } of the block's keys");
    return TD_OK;
}

/* The controller the API made of block `member` into *out, or its error, located: at the key of
 * the block it names (touchdown/error.h: site.field), else at the block. */
static td_status made(td_case_reader *r, const config_setting_t *member, td_controller *k, const td_error *merr,
                      td_controller **out)
{
    *out = k;
    if (k)
        return TD_OK;
    if (merr->code == TD_ERR_NOMEM)
        return td_error_set(r->err, TD_ERR_NOMEM, "%s: %s", r->path_shown, merr->message);
    return td_cr_model_fail(r, member, merr->code, merr);
}

/* The sample rate of a block in `domain` (0: s), or a failure naming its domain key. */
static td_status block_rate(td_case_reader *r, const config_setting_t *g, int domain, double sample_rate, double *rate)
{
    *rate = domain == 1 ? sample_rate : 0.0;
    if (domain == 1 && !(sample_rate > 0.0))
        return td_cr_fail(r, config_setting_get_member(g, "domain"), NULL,
                          "a block in z needs the controller's sample_rate (absent: the controller is continuous)");
    return TD_OK;
}

static td_status make_tf(td_case_reader *r, const config_setting_t *g, double sample_rate, double *rate,
                         td_controller **out)
{
    cb_tf tf;
    td_error merr;
    td_status st;
    memset(&tf, 0, sizeof tf);
    st = td_cs_read(r, g, &tf_table, &tf);
    if (st == TD_OK)
        st = block_rate(r, g, tf.domain, sample_rate, rate);
    if (st == TD_OK && (tf.n_num == 0 || tf.n_den == 0))
        st = td_cr_missing(r, g, tf.n_num == 0 ? "num" : "den", "coefficients [ ... ]");
    if (st != TD_OK)
        return st;
    return made(r, g, td_controller_create_tf(tf.num, tf.n_num, tf.den, tf.n_den, *rate, &merr), &merr, out);
}

static td_status make_zpk(td_case_reader *r, const config_setting_t *g, double sample_rate, double *rate,
                          td_controller **out)
{
    cb_zpk z;
    td_error merr;
    td_status st;
    memset(&z, 0, sizeof z);
    z.gain = 1.0;
    st = td_cs_read(r, g, &zpk_table, &z);
    if (st == TD_OK)
        st = block_rate(r, g, z.domain, sample_rate, rate);
    if (st != TD_OK)
        return st;
    return made(r, g,
                td_controller_create_zpk(z.zero_re, z.zero_im, z.n_zeros, z.pole_re, z.pole_im, z.n_poles, z.gain,
                                         *rate, &merr),
                &merr, out);
}

/* The shape of matrix `which` (0..3: A..D) against n states: a failure naming it, or TD_OK. */
static td_status ss_shape(td_case_reader *r, const config_setting_t *g, const cb_ss *ss, int which, int n)
{
    static const char *const want[] = {"n x n", "n x 1 (one row [b] per state)", "1 x n", "1 x 1"};
    const int rows[] = {n, n, 1, 1}, cols[] = {n, 1, n, 1};
    char key[2] = {0, 0};
    const config_setting_t *s;
    key[0] = (char)('A' + which);
    s = config_setting_get_member(g, key);
    if (ss->rows[which] == rows[which] && ss->cols[which] == cols[which])
        return TD_OK;
    if (which == 3 && !s)
        return td_cr_missing(r, g, "D", "feedthrough, 1 x 1: ([d])");
    if (n == 0 && (which == 1 || which == 2) && ss->rows[which] == 0)
        return TD_OK; /* no state: B and C may be left out */
    return td_cr_fail(r, s ? s : g, s ? NULL : key, "is %d x %d; %s must be %s, with n = %d states (the rows of A)",
                      ss->rows[which], ss->cols[which], key, want[which], n);
}

static td_status make_ss(td_case_reader *r, const config_setting_t *g, double sample_rate, double *rate,
                         td_controller **out)
{
    static const cb_ss zero;
    cb_ss ss = zero;
    double A[CB_MAX_ORDER * CB_MAX_ORDER], B[CB_MAX_ORDER], C[CB_MAX_ORDER];
    int i, j, n, which;
    td_error merr;
    td_status st = td_cs_read(r, g, &ss_table, &ss);
    if (st == TD_OK)
        st = block_rate(r, g, ss.domain, sample_rate, rate);
    n = ss.rows[0];
    for (which = 0; st == TD_OK && which < 4; which++)
        st = ss_shape(r, g, &ss, which, n);
    if (st != TD_OK)
        return st;
    for (i = 0; i < n; i++) {
        B[i] = ss.m[1][i * CB_MAX_ORDER];
        C[i] = ss.m[2][i];
        for (j = 0; j < n; j++)
            A[i + j * n] = ss.m[0][i * CB_MAX_ORDER + j]; /* column-major */
    }
    return made(r, g, td_controller_create_ss(n, 1, 1, A, B, C, ss.m[3], NULL, *rate, &merr), &merr, out);
}

/* A block of a fixed form (gain, pid, leadlag, lowpass, notch, resonant): continuous. */
static td_status make_fixed(td_case_reader *r, const config_setting_t *member, int kind, td_controller **out)
{
    union {
        td_pid_block pid;
        td_leadlag_block leadlag;
        td_lowpass_block lowpass;
        td_notch_block notch;
        td_resonant_block resonant;
    } b;
    double k;
    td_error merr;
    td_status st;
    memset(&b, 0, sizeof b);
    if (kind == CB_GAIN) {
        st = td_cr_value_real(r, member, TD_CR_FINITE, &k);
        return st == TD_OK ? made(r, member, td_controller_create_gain(k, &merr), &merr, out) : st;
    }
    if (kind == CB_LOWPASS)
        lowpass_preset(&b.lowpass);
    if ((st = td_cs_read(r, member, block_keys[kind].sub, &b)) != TD_OK)
        return st;
    if (kind == CB_LOWPASS && b.lowpass.order == 1 && td_cr_has(member, "damping"))
        return td_cr_fail(r, config_setting_get_member(member, "damping"), NULL,
                          "a first-order low-pass has no damping");
    switch (kind) {
    case CB_PID: return made(r, member, td_controller_create_pid(&b.pid, &merr), &merr, out);
    case CB_LEADLAG: return made(r, member, td_controller_create_leadlag(&b.leadlag, &merr), &merr, out);
    case CB_LOWPASS: return made(r, member, td_controller_create_lowpass(&b.lowpass, &merr), &merr, out);
    case CB_NOTCH: return made(r, member, td_controller_create_notch(&b.notch, &merr), &merr, out);
    default: return made(r, member, td_controller_create_resonant(&b.resonant, &merr), &merr, out);
    }
}

/* *acc then k (k alone when *acc is NULL), joined by `join` (series or parallel), freeing both; a
 * failure located at e. */
static td_status join_at(td_case_reader *r, const config_setting_t *e, td_controller **acc, td_controller *k,
                         td_controller *(*join)(const td_controller *, const td_controller *, td_error *))
{
    td_controller *j;
    td_error merr;
    if (!*acc) {
        *acc = k;
        return TD_OK;
    }
    j = join(*acc, k, &merr);
    td_controller_free(acc);
    td_controller_free(&k);
    *acc = j;
    return j ? TD_OK : td_cr_model_fail(r, e, merr.code, &merr);
}

/* Reads member i of a list into *out (*sampled: in z), *e the member (where a failure is located). */
typedef td_status (*cb_member_reader)(td_case_reader *r, const config_setting_t *list, int i, double sample_rate,
                                      const config_setting_t **e, td_controller **out, int *sampled);

/* The members of `list`, read by `read` and joined by `join` (series or parallel) into *out, every one
 * in s or every one in z (*sampled says which); `mixed` is the message for a member in the other
 * domain, its two %s this member's domain and the first's. */
static td_status join_members(td_case_reader *r, const config_setting_t *list, double sample_rate,
                              cb_member_reader read,
                              td_controller *(*join)(const td_controller *, const td_controller *, td_error *),
                              const char *mixed, td_controller **out, int *sampled)
{
    const config_setting_t *e = list;
    td_controller *b = NULL;
    int i, s = 0;
    td_status st = TD_OK;
    *out = NULL;
    for (i = 0; st == TD_OK && i < config_setting_length(list); i++) {
        st = read(r, list, i, sample_rate, &e, &b, &s);
        if (st == TD_OK && i > 0 && s != *sampled)
            st = td_cr_fail(r, e, NULL, mixed, s ? "z" : "s", s ? "s" : "z");
        *sampled = i == 0 ? s : *sampled;
        if (st == TD_OK)
            st = join_at(r, e, out, b, join); /* takes b */
        else
            td_controller_free(&b);
        b = NULL;
    }
    if (st != TD_OK)
        td_controller_free(out);
    return st;
}

/* Member i of a branch's list of blocks in series: a block { ... }. */
static td_status read_series_member(td_case_reader *r, const config_setting_t *list, int i, double sample_rate,
                                    const config_setting_t **e, td_controller **out, int *sampled)
{
    td_status st = td_cr_entry(r, list, i, e);
    if (st != TD_OK) {
        *e = config_setting_get_elem(list, (unsigned)i);
        return st;
    }
    return td_cr_read_block(r, *e, sample_rate, out, sampled);
}

/* Branch i of a parallel block: a block, or a list of blocks in series, every one in s or every one
 * in z (*sampled says which). */
static td_status read_branch(td_case_reader *r, const config_setting_t *list, int i, double sample_rate,
                             const config_setting_t **e, td_controller **out, int *sampled)
{
    const config_setting_t *br = config_setting_get_elem(list, (unsigned)i);
    *e = br;
    *out = NULL;
    if (config_setting_is_group(br))
        return td_cr_read_block(r, br, sample_rate, out, sampled);
    if (!config_setting_is_list(br) || config_setting_length(br) == 0)
        return td_cr_fail(r, br, NULL, "expected a branch: a block { ... } or a list of blocks ( { ... }, ... )");
    return join_members(r, br, sample_rate, read_series_member, td_controller_series,
                        "a branch of a parallel block is all in s or all in z (this block is in %s, the "
                        "branch's first in %s)",
                        out, sampled);
}

/* A parallel block: its branches summed, all continuous or all sampled (*rate: 0 or sample_rate). */
static td_status make_parallel(td_case_reader *r, const config_setting_t *list, double sample_rate, double *rate,
                               td_controller **out)
{
    int sampled = 0;
    td_status st = join_members(r, list, sample_rate, read_branch, td_controller_parallel,
                                "the branches of a parallel block are all in s or all in z (this branch is "
                                "in %s, the first in %s)",
                                out, &sampled);
    *rate = sampled ? sample_rate : 0.0;
    return st;
}

td_status td_cr_read_block(td_case_reader *r, const config_setting_t *e, double sample_rate, td_controller **out,
                           int *sampled)
{
    const config_setting_t *member = NULL;
    double rate = 0.0;
    int kind = 0;
    td_status st = block_member(r, e, &member, &kind);
    *out = NULL;
    *sampled = 0;
    if (st != TD_OK)
        return st;
    switch (kind) {
    case CB_TF: st = make_tf(r, member, sample_rate, &rate, out); break;
    case CB_ZPK: st = make_zpk(r, member, sample_rate, &rate, out); break;
    case CB_SS: st = make_ss(r, member, sample_rate, &rate, out); break;
    case CB_PARALLEL: st = make_parallel(r, member, sample_rate, &rate, out); break;
    default: st = make_fixed(r, member, kind, out); break;
    }
    *sampled = st == TD_OK && rate > 0.0;
    return st;
}
