/* touchdown report: the report's text and JSON forms (docs/report.md). A quantity without a value
 * is written in words ("not in this file", "not computed", "not an answer") and as null, never as
 * a number; an incomplete run says so on its first line. */
#include "report/report.h"

#include "common/cli.h"
#include "touchdown/assess.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- text ------------------------------------------------------------------------------------ */

/* The value of an item in words: "1234.5 N", "zone D", "not in this file". */
static void value_words(const report *rep, const report_item *it, char *buf, size_t n)
{
    if (it->def->id == TD_OUT_SUM_SETTLE_TIME && it->state == REPORT_UNDEFINED && rep->settled == 0)
        snprintf(buf, n, "not settled within the run");
    else if (it->state != REPORT_VALUE)
        snprintf(buf, n, "%s", report_state_words(it->state));
    else if (it->def->limit == REPORT_LIMIT_ZONE)
        snprintf(buf, n, "zone %s", td_vibration_zone_name(it->value == floor(it->value) ? (int)it->value : -1));
    else if (!it->units[0] || !strcmp(it->units, "1")) /* a ratio or a count */
        snprintf(buf, n, "%.6g", it->value);
    else
        snprintf(buf, n, "%.6g %s", it->value, it->units);
}

/* The limit of an item in words ("-" when none applies). */
static void limit_words(const report_item *it, const report_limits *lim, char *buf, size_t n)
{
    double c0 = it->part >= 0 && it->part < REPORT_MAX_PARTS ? lim->static_rating[it->part] : NAN;
    switch (isnan(it->limit) ? REPORT_LIMIT_NONE : it->def->limit) {
    case REPORT_LIMIT_RATIO:
        if (isnan(c0))
            snprintf(buf, n, "1 (ISO 76)");
        else
            snprintf(buf, n, "1 (C0 %.6g N, ISO 76)", c0);
        break;
    case REPORT_LIMIT_TEMPERATURE: snprintf(buf, n, "%.6g K (limits)", it->limit); break;
    case REPORT_LIMIT_DROPS: snprintf(buf, n, "at least %.6g (limits)", it->limit); break;
    case REPORT_LIMIT_ZONE: snprintf(buf, n, "zone %s at most (limits)", td_vibration_zone_name((int)it->limit)); break;
    case REPORT_LIMIT_STRESS: snprintf(buf, n, "%.6g MPa (ISO 76)", it->limit / 1e6); break;
    default: snprintf(buf, n, "%s", it->def->limit == REPORT_LIMIT_NONE ? "-" : "none given"); break;
    }
}

static void text_item(FILE *f, const report *rep, const report_item *it)
{
    char value[160], limit[96], label[128];
    value_words(rep, it, value, sizeof value);
    limit_words(it, &rep->lim, limit, sizeof limit);
    snprintf(label, sizeof label, "%s%s", it->def->label, it->def->run_total ? ", over the run" : "");
    fprintf(f, "  %-52s %-26s %-26s %s%s\n", label, value, limit, report_verdict_words(it->verdict),
            it->converges == 0 ? "  [does not converge with the mesh]" : "");
}

/* "12.5 K" or "none given" into buf. */
static const char *given(char *buf, size_t n, double v, const char *unit)
{
    if (isnan(v))
        snprintf(buf, n, "none given");
    else
        snprintf(buf, n, "%.6g%s", v, unit);
    return buf;
}

/* The case's limits and ratings, as read from its text. */
static void text_limits(FILE *f, const report_limits *lim, int nret)
{
    char a[64], b[64];
    int k;
    fprintf(f, "limits        from the case: temperature rise %s, drops %s",
            given(a, sizeof a, lim->temperature_rise, " K"), given(b, sizeof b, lim->drops, ""));
    fprintf(f, ", ISO 14839-2 zone boundaries %.3g, %.3g, %.3g of C_min, zone %s at most\n", lim->zones[0],
            lim->zones[1], lim->zones[2], td_vibration_zone_name((int)lim->zone));
    for (k = 0; k < nret && k < REPORT_MAX_PARTS; k++)
        fprintf(f, "              retainer %d bearing: static rating C0 %s, dynamic rating C %s\n", k,
                given(a, sizeof a, lim->static_rating[k], " N"), given(b, sizeof b, lim->dynamic_rating[k], " N"));
}

/* The first lines: what the file is, whether the run completed, the case's limits. */
static void text_header(FILE *f, const report *rep)
{
    if (!rep->complete)
        fprintf(f,
                "THE RUN DID NOT COMPLETE: it stopped at %.10g s of %.10g s; none of its numbers is given as an\n"
                "answer.\nwhy           %s\n\n",
                rep->t_reached, rep->t_end,
                rep->flag < 0    ? "no completeness flag: the writer was stopped"
                : rep->reason[0] ? rep->reason
                                 : "no reason given");
    fprintf(f, "drop report of %s\n", rep->path);
    fprintf(f, "case          %s\n", rep->description[0] ? rep->description : "(no description)");
    fprintf(f, "run           %s, %.10g s to %.10g s (requested %.10g s), written by touchdown %s\n",
            rep->complete ? "complete" : "INCOMPLETE", rep->t_start, rep->t_reached, rep->t_end,
            rep->version[0] ? rep->version : "(version not in this file)");
    fprintf(f,
            "over the run  %.10g s to %.10g s: the totals so marked are this run's, a drop's only when it\n"
            "              ended at rest (final speed %.6g of %.6g rad/s: %s)\n",
            rep->t_start, rep->t_reached, rep->final_speed, rep->speed,
            rep->at_rest ? "at rest" : "not at rest, a total within its limit is not judged");
    fprintf(f, "ending        %s\n",
            !rep->complete   ? "not an answer (the run did not complete)"
            : rep->ending[0] ? rep->ending
                             : "not in this file");
    if (!rep->lim.read)
        fprintf(f, "limits        none: %s\n", rep->lim.why);
    else
        text_limits(f, &rep->lim, rep->nret);
    fprintf(f, "\n  %-52s %-26s %-26s %s\n", "quantity", "value", "limit", "verdict");
}

void report_write_text(FILE *f, const report *rep)
{
    int i, per = -1, part = -2;
    text_header(f, rep);
    for (i = 0; i < rep->n; i++) {
        const report_item *it = &rep->items[i];
        if (it->def->per != per || it->part != part) {
            per = it->def->per, part = it->part;
            if (per == 0)
                fprintf(f, "the drop\n");
            else
                fprintf(f, "%s %d\n", per == 1 ? "retainer" : "sensor of AMB", part);
        }
        text_item(f, rep, it);
    }
    if (rep->nret > REPORT_MAX_PARTS || rep->namb > REPORT_MAX_PARTS)
        fprintf(f, "(the first %d retainers and sensors only)\n", REPORT_MAX_PARTS);
}

/* ---- JSON ------------------------------------------------------------------------------------ */

static void json_number(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.17g", v);
    else
        fputs("null", f);
}

/* "key":"text", or null when text is empty */
static void json_text(FILE *f, const char *key, const char *text)
{
    fprintf(f, "\"%s\":", key);
    if (text[0])
        td_cli_json_string(f, text);
    else
        fputs("null", f);
}

static void json_item(FILE *f, const report_item *it)
{
    fprintf(f, "{\"name\":\"%s\",\"label\":", td_out_name(it->def->id));
    td_cli_json_string(f, it->def->label);
    fprintf(f, ",\"%s\":", it->def->per == 2 ? "sensor" : "retainer");
    if (it->part >= 0)
        fprintf(f, "%d", it->part);
    else
        fputs("null", f);
    fputs(",\"value\":", f);
    json_number(f, it->state == REPORT_VALUE ? it->value : NAN);
    fputs(",\"units\":", f);
    td_cli_json_string(f, it->units);
    fprintf(f, ",\"state\":\"%s\",\"limit\":", it->state == REPORT_VALUE ? "value" : report_state_words(it->state));
    json_number(f, it->limit);
    fputs(",\"verdict\":", f);
    if (it->verdict == REPORT_NOT_JUDGED)
        fputs("null", f);
    else /* the text's "-" of a value with no limit is "no limit" here */
        fprintf(f, "\"%s\"", it->verdict == REPORT_NO_LIMIT ? "no limit" : report_verdict_words(it->verdict));
    fprintf(f, ",\"converges\":%s,\"over_the_run\":%s}",
            it->converges < 0 ? "null"
            : it->converges   ? "true"
                              : "false",
            it->def->run_total ? "true" : "false");
}

static void json_limits(FILE *f, const report *rep)
{
    int k, n = rep->nret < REPORT_MAX_PARTS ? rep->nret : REPORT_MAX_PARTS;
    fprintf(f, "\"limits\":{\"from_case\":%s,", rep->lim.read ? "true" : "false");
    json_text(f, "why_none", rep->lim.read ? "" : rep->lim.why);
    fputs(",\"temperature_rise\":", f);
    json_number(f, rep->lim.temperature_rise);
    fputs(",\"drops\":", f);
    json_number(f, rep->lim.drops);
    fputs(",\"zones\":", f);
    if (isnan(rep->lim.zones[0]))
        fputs("null", f);
    else
        fprintf(f, "[%.17g,%.17g,%.17g]", rep->lim.zones[0], rep->lim.zones[1], rep->lim.zones[2]);
    fputs(",\"zone\":", f);
    if (isnan(rep->lim.zone))
        fputs("null", f);
    else
        fprintf(f, "\"%s\"", td_vibration_zone_name((int)rep->lim.zone));
    fputs(",\"static_rating\":[", f);
    for (k = 0; k < n; k++) {
        fputs(k ? "," : "", f);
        json_number(f, rep->lim.static_rating[k]);
    }
    fputs("],\"dynamic_rating\":[", f);
    for (k = 0; k < n; k++) {
        fputs(k ? "," : "", f);
        json_number(f, rep->lim.dynamic_rating[k]);
    }
    fputs("]}", f);
}

void report_write_json(FILE *f, const report *rep)
{
    int i;
    fputs("{\"file\":", f);
    td_cli_json_string(f, rep->path);
    fprintf(f, ",\"complete\":%s,", rep->complete ? "true" : "false");
    json_text(f, "incomplete_reason", rep->complete ? "" : rep->reason[0] ? rep->reason : "no reason given");
    fputc(',', f);
    json_text(f, "description", rep->description);
    fputc(',', f);
    json_text(f, "library_version", rep->version);
    fputs(",\"t_start\":", f);
    json_number(f, rep->t_start);
    fputs(",\"t_end\":", f);
    json_number(f, rep->t_end);
    fputs(",\"t_reached\":", f);
    json_number(f, rep->t_reached);
    fputc(',', f);
    json_text(f, "ending", rep->complete ? rep->ending : "");
    fprintf(f, ",\"retainers\":%d,\"sensors\":%d,", rep->nret, rep->namb);
    json_limits(f, rep);
    fputs(",\"quantities\":[", f);
    for (i = 0; i < rep->n; i++) {
        fputs(i ? "," : "", f);
        json_item(f, &rep->items[i]);
    }
    fputs("]}\n", f);
}
