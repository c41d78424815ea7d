/*
 * Where a setting is and what it is called, and the one error format of the case reader:
 * "FILE:LINE: KEY: what is wrong" ("FILE: --set 'K=V': KEY: ..." for overridden values), with
 * user text made fit to quote. The bottom layer of lib/case (case_internal.h): it calls no other
 * file of the reader.
 */
#include "case/case_internal.h"
#include "util/error_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Bytes needed to show ch: 1, 2 for \n \t \r, 4 for \xHH. */
static size_t shown_width(unsigned char ch)
{
    if (ch == '\n' || ch == '\t' || ch == '\r')
        return 2;
    return ch < 0x20 || ch == 0x7f ? 4 : 1;
}

static void show_char(unsigned char ch, char *out)
{
    static const char hex[] = "0123456789abcdef";
    if (shown_width(ch) == 1) {
        out[0] = (char)ch;
    } else if (shown_width(ch) == 2) {
        out[0] = '\\';
        out[1] = ch == '\n' ? 'n' : ch == '\t' ? 't' : 'r';
    } else {
        out[0] = '\\';
        out[1] = 'x';
        out[2] = hex[ch >> 4];
        out[3] = hex[ch & 15];
    }
}

const char *td_cr_printable(const char *s, char *buf, size_t n)
{
    size_t len = 0;
    const unsigned char *p = (const unsigned char *)s;
    for (; *p; p++) {
        size_t w = shown_width(*p);
        if (len + w + 1 > n) {
            /* cut: make room for "..." and the NUL */
            while (len > 0 && len + 4 > n)
                len--;
            if (len + 4 <= n) {
                memcpy(buf + len, "...", 3);
                len += 3;
            }
            break;
        }
        show_char(*p, buf + len);
        len += w;
    }
    buf[len] = '\0';
    return buf;
}

char *td_cr_printable_dup(const char *s)
{
    size_t n = 1;
    const unsigned char *p;
    char *buf;
    for (p = (const unsigned char *)s; *p; p++)
        n += shown_width(*p);
    buf = malloc(n);
    return buf ? (char *)td_cr_printable(s, buf, n) : NULL;
}

void td_cr_file_shown(const td_case_reader *r, const char *file, char *buf, size_t n)
{
    char name[1024];
    if (!file)
        snprintf(buf, n, "%s", r->path_shown);
    else if (r->has_dir)
        snprintf(buf, n, "%s/%s", r->dir_shown, td_cr_printable(file, name, sizeof name));
    else
        snprintf(buf, n, "%s", td_cr_printable(file, name, sizeof name));
}

void td_cr_key(const config_setting_t *s, char *buf, size_t n)
{
    const config_setting_t *parent;
    size_t len;
    buf[0] = '\0';
    if (!s || !(parent = config_setting_parent(s)))
        return;
    td_cr_key(parent, buf, n);
    len = strlen(buf);
    if (config_setting_is_list(parent) || config_setting_is_array(parent))
        snprintf(buf + len, n - len, "[%d]", config_setting_index(s));
    else
        snprintf(buf + len, n - len, "%s%s", len ? "." : "", config_setting_name(s));
}

/* The override string that created s or one of its parents, or NULL. */
static const char *override_of(const config_setting_t *s)
{
    for (; s; s = config_setting_parent(s))
        if (config_setting_get_hook(s))
            return (const char *)config_setting_get_hook(s);
    return NULL;
}

/* The entry of the case's "overrides" list whose string is `ov`, or NULL (a --set). */
static const config_setting_t *file_override(const td_case_reader *r, const char *ov)
{
    int i, n = r->overrides ? config_setting_length(r->overrides) : 0;
    for (i = 0; i < n; i++) {
        const config_setting_t *e = config_setting_get_elem(r->overrides, (unsigned)i);
        if (config_setting_get_string(e) == ov)
            return e;
    }
    return NULL;
}

void td_cr_blame_override(const td_case_reader *r, const char *ov)
{
    int i;
    for (i = 0; r->err && ov && i < r->n_sets; i++)
        if (r->sets[i] == ov) { /* the hook is the caller's string itself (case_override.c) */
            r->err->site = (td_error_site){"override", i, NULL};
            return;
        }
}

void td_cr_where(const td_case_reader *r, const config_setting_t *s, char *buf, size_t n)
{
    const char *ov = override_of(s);
    const config_setting_t *entry = ov ? file_override(r, ov) : NULL;
    char shown[1024], at[1024], key[256];
    if (entry) { /* grafted by the case's own overrides list: where that entry is */
        td_cr_where(r, entry, at, sizeof at);
        td_cr_key(entry, key, sizeof key);
        snprintf(buf, n, "%s: %s: '%s'", at, key, td_cr_printable(ov, shown, sizeof shown));
        return;
    }
    if (ov) {
        snprintf(buf, n, "%s: --set '%s'", r->path_shown, td_cr_printable(ov, shown, sizeof shown));
        return;
    }
    td_cr_file_shown(r, s ? config_setting_source_file(s) : NULL, shown, sizeof shown);
    /* the root group has no line of its own: point at the top of the file */
    snprintf(buf, n, "%s:%u", shown, s && config_setting_source_line(s) ? config_setting_source_line(s) : 1u);
}

const config_setting_t *td_cr_shaft_nodes(const td_case_reader *r)
{
    const config_setting_t *shaft = config_setting_get_member(config_root_setting(&r->cfg), "shaft");
    const config_setting_t *s = shaft ? config_setting_get_member(shaft, "nodes") : NULL;
    if (!s && shaft)
        s = config_setting_get_member(shaft, "elements"); /* length + elements: elements + 1 nodes */
    return s ? s : shaft;
}

void td_cr_where_list(const td_case_reader *r, const config_setting_t *list, const char *member, char *buf, size_t n)
{
    int i, count = list && config_setting_is_aggregate(list) ? config_setting_length(list) : 0;
    for (i = 0; i < count; i++) {
        const config_setting_t *e = config_setting_get_elem(list, (unsigned)i);
        const config_setting_t *t = member ? config_setting_get_member(e, member) : e;
        if (t && override_of(t)) {
            td_cr_where(r, t, buf, n);
            return;
        }
    }
    td_cr_where(r, list, buf, n);
}

td_status td_cr_fail(td_case_reader *r, const config_setting_t *s, const char *sub, const char *fmt, ...)
{
    char where[2048], key[512], msg[TD_ERROR_MESSAGE_SIZE];
    size_t len;
    va_list ap;
    td_cr_where(r, s, where, sizeof where);
    td_cr_key(s, key, sizeof key);
    len = strlen(key);
    if (sub)
        snprintf(key + len, sizeof key - len, "%s%s", len ? "." : "", sub);
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (key[0]) {
        len = strlen(where);
        snprintf(where + len, sizeof where - len, ": %s", key);
    }
    /* a long override or path is cut in its middle; the reason stays whole */
    td_error_set_reason(r->err, TD_ERR_PARSE, where, msg);
    td_cr_blame_override(r, override_of(s));
    return TD_ERR_PARSE;
}

td_status td_cr_fail_vs(td_case_reader *r, const config_setting_t *s, const config_setting_t *other, const char *fmt,
                        ...)
{
    char msg[TD_ERROR_MESSAGE_SIZE], key[512], where[1200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (!other || other == s)
        return td_cr_fail(r, s, NULL, "%s", msg);
    td_cr_key(other, key, sizeof key);
    td_cr_where(r, other, where, sizeof where);
    return td_cr_fail(r, s, NULL, "%s; see %s at %s", msg, key, where);
}

td_status td_cr_fail_file(td_error *err, td_status code, const char *shown, int line, const char *fmt, ...)
{
    char where[8192], msg[TD_ERROR_MESSAGE_SIZE];
    va_list ap;
    if (line > 0)
        snprintf(where, sizeof where, "%s:%d", shown, line);
    else
        snprintf(where, sizeof where, "%s", shown);
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return td_error_set_reason(err, code, where, msg);
}
