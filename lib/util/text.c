/* Text buffers (util/text.h), the JSON string escape (touchdown/json.h) and exact short numbers. */
#include "util/text.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "touchdown/json.h"

void td_text_fixed(td_text *t, char *buf, size_t n)
{
    t->data = buf;
    t->len = 0;
    t->cap = n;
    t->fixed = 1;
    t->failed = 0;
    if (n > 0)
        buf[0] = '\0';
}

/* Room for `extra` more bytes and the NUL in a growable text; 0 (and `failed` set) if none. */
static int reserve(td_text *t, size_t extra)
{
    size_t cap = t->cap ? t->cap : 1024;
    char *p;
    if (t->failed)
        return 0;
    if (t->len + extra + 1 <= t->cap)
        return 1;
    while (cap < t->len + extra + 1)
        cap *= 2;
    p = realloc(t->data, cap);
    if (!p) {
        t->failed = 1;
        return 0;
    }
    t->data = p;
    t->cap = cap;
    return 1;
}

void td_text_append(td_text *t, const char *s, size_t n)
{
    if (t->fixed) {
        if (t->len + 1 < t->cap) {
            size_t k = n < t->cap - 1 - t->len ? n : t->cap - 1 - t->len;
            memcpy(t->data + t->len, s, k);
            t->data[t->len + k] = '\0';
        }
        t->len += n;
        return;
    }
    if (!reserve(t, n))
        return;
    memcpy(t->data + t->len, s, n);
    t->len += n;
    t->data[t->len] = '\0';
}

void td_text_printf(td_text *t, const char *fmt, ...)
{
    va_list ap;
    int k;
    va_start(ap, fmt);
    if (t->fixed) {
        k = vsnprintf(t->len < t->cap ? t->data + t->len : NULL, t->len < t->cap ? t->cap - t->len : 0, fmt, ap);
    } else {
        va_list aq;
        va_copy(aq, ap);
        k = vsnprintf(NULL, 0, fmt, aq);
        va_end(aq);
        if (k >= 0 && reserve(t, (size_t)k))
            vsnprintf(t->data + t->len, (size_t)k + 1, fmt, ap);
        else
            k = 0;
    }
    va_end(ap);
    if (k > 0)
        t->len += (size_t)k;
}

void td_text_json_string(td_text *t, const char *s)
{
    td_text_append(t, "\"", 1);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            td_text_printf(t, "\\%c", c);
        else if (c < 0x20)
            td_text_printf(t, "\\u%04x", c);
        else
            td_text_append(t, s, 1);
    }
    td_text_append(t, "\"", 1);
}

void td_text_json_real(td_text *t, double x)
{
    if (isfinite(x))
        td_text_printf(t, "%.17g", x);
    else
        td_text_append(t, "null", 4);
}

int td_json_string(char *buf, size_t n, const char *s)
{
    td_text t;
    td_text_fixed(&t, buf, n);
    td_text_json_string(&t, s ? s : "");
    return (int)t.len;
}

void td_text_shortest_number(char *buf, size_t n, double x)
{
    int digits;
    for (digits = 15; digits <= 17; digits++) {
        snprintf(buf, n, "%.*g", digits, x);
        if (strtod(buf, NULL) == x)
            return;
    }
}
