/* touchdown report: the limits of the case a run file holds as text (TD_OUT_CASE_TEXT: the case
 * file with its @include files expanded in place and its --set overrides as comment lines, which
 * the case reader reads back as it read the file; the FMU stages the same text). */
#include "report/report.h"

#include "touchdown/case.h"
#include "touchdown/dofs.h"
#include "touchdown/model.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The comment lines the case reader writes for the overrides (touchdown/case.h). */
static const char overrides_mark[] = TD_CASE_TEXT_OVERRIDES;
static const char set_mark[] = TD_CASE_TEXT_SET;

/* The overrides recorded at the end of the text, as malloc'd strings into ov (at most max);
 * their number. */
static int recorded_overrides(const char *text, char **ov, int max)
{
    const char *p = strstr(text, overrides_mark);
    int n = 0;
    while (p && *p && n < max) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len > sizeof set_mark - 1 && !strncmp(p, set_mark, sizeof set_mark - 1)) {
            size_t k = len - (sizeof set_mark - 1);
            if ((ov[n] = malloc(k + 1)) != NULL) {
                memcpy(ov[n], p + sizeof set_mark - 1, k);
                ov[n++][k] = '\0';
            }
        }
        p = end ? end + 1 : NULL;
    }
    return n;
}

/* Write the text to a new temporary file; its path into path (n bytes), 0, else -1 with why. */
static int temporary_case(const char *text, char *path, size_t n, report_limits *lim)
{
    const char *dir = getenv("TMPDIR");
    size_t len = strlen(text);
    int fd, ok;
    if (snprintf(path, n, "%s/touchdown-report-case.XXXXXX", dir && *dir ? dir : "/tmp") >= (int)n ||
        (fd = mkstemp(path)) < 0) {
        snprintf(lim->why, sizeof lim->why, "no temporary file for the case text: %s", strerror(errno));
        return -1;
    }
    ok = write(fd, text, len) == (ssize_t)len;
    ok = close(fd) == 0 && ok;
    if (!ok) {
        snprintf(lim->why, sizeof lim->why, "the case text could not be written to %.400s", path);
        remove(path);
        return -1;
    }
    return 0;
}

/* The limits and the bearings' ratings the case's model holds (td_model_get_limits,
 * td_model_get_retainer_bearing: 0 a rating not given). */
static void model_limits(const td_model *m, int nret, report_limits *lim)
{
    td_limits l;
    int k;
    td_model_get_limits(m, &l);
    lim->temperature_rise = l.temperature_rise;
    lim->drops = l.drops;
    lim->zones[0] = l.zones.ab, lim->zones[1] = l.zones.bc, lim->zones[2] = l.zones.cd;
    lim->zone = l.zone;
    for (k = 0; k < nret && k < REPORT_MAX_PARTS && k < td_model_retainer_count(m); k++) {
        td_retainer_bearing b;
        if (td_model_get_retainer_bearing(m, k, &b) != TD_OK)
            continue;
        lim->static_rating[k] = b.static_rating > 0.0 ? b.static_rating : TD_UNDEFINED;
        lim->dynamic_rating[k] = b.dynamic_rating > 0.0 ? b.dynamic_rating : TD_UNDEFINED;
    }
}

void report_case_limits(const char *case_text, int nret, report_limits *lim, char *desc, size_t n)
{
    char path[4096], *ov[64];
    int i, nov;
    td_case *c = NULL;
    td_error err;
    memset(lim, 0, sizeof *lim);
    lim->temperature_rise = lim->drops = TD_UNDEFINED;
    for (i = 0; i < 3; i++)
        lim->zones[i] = TD_UNDEFINED;
    lim->zone = TD_UNDEFINED; /* no case text: no limit */
    for (i = 0; i < REPORT_MAX_PARTS; i++)
        lim->static_rating[i] = lim->dynamic_rating[i] = TD_UNDEFINED;
    desc[0] = '\0';
    if (!case_text) {
        snprintf(lim->why, sizeof lim->why, "the file holds no case text");
        return;
    }
    if (temporary_case(case_text, path, sizeof path, lim))
        return;
    nov = recorded_overrides(case_text, ov, (int)(sizeof ov / sizeof ov[0]));
    if (td_case_load(path, (const char *const *)ov, nov, &c, &err) == TD_OK) {
        lim->read = 1;
        snprintf(desc, n, "%s", td_case_description(c));
        model_limits(td_case_model(c), nret, lim);
        td_case_free(&c);
    } else {
        snprintf(lim->why, sizeof lim->why, "its case text could not be read: %s", err.message);
    }
    remove(path);
    for (i = 0; i < nov; i++)
        free(ov[i]);
}
