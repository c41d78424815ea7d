/*
 * Case-file text: reading files safely (regular files only, size limit, no binary data) and
 * keeping the list of files read (td_case_files), expanding @include in place for td_case_text,
 * and two guards against libconfig 1.5 defects
 * that its parser reports nowhere:
 *   - integer literals beyond 32 bits are silently wrapped (10000000000 reads as 1410065408);
 *   - an unterminated block comment silently drops the rest of the file.
 * The scan only tokenises comments, strings and numbers; all parsing stays with libconfig.
 */
#include "case/case_internal.h"
#include "util/error_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* A control character that does not belong in a text file (NUL, BEL, ESC, ...). */
static int binary_byte(unsigned char ch)
{
    return (ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r' && ch != '\f' && ch != '\v') || ch == 0x7f;
}

td_status td_cr_read_file(const char *what, const char *shown, const char *path, char **text, td_error *err)
{
    struct stat st;
    FILE *f;
    char *buf;
    size_t n, i;
    int line = 1;

    *text = NULL;
    if (stat(path, &st) != 0)
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "cannot read the %s: %s", what, strerror(errno));
    if (S_ISDIR(st.st_mode))
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "cannot read the %s: it is a directory", what);
    if (!S_ISREG(st.st_mode)) /* FIFOs and devices could block or never end */
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "cannot read the %s: not a regular file", what);
    if ((long long)st.st_size > (long long)TD_CASE_MAX_FILE_SIZE)
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "the %s is too large (%lld bytes, limit %ld)", what,
                               (long long)st.st_size, (long)TD_CASE_MAX_FILE_SIZE);
    f = fopen(path, "rb");
    if (!f)
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "cannot read the %s: %s", what, strerror(errno));
    buf = malloc((size_t)st.st_size + 1);
    if (!buf) {
        fclose(f);
        return td_cr_fail_file(err, TD_ERR_NOMEM, shown, 0, "out of memory reading the %s", what);
    }
    /* read at most the size stat() saw; a file growing meanwhile is cut there */
    n = fread(buf, 1, (size_t)st.st_size, f);
    if (ferror(f)) {
        int e = errno;
        fclose(f);
        free(buf);
        return td_cr_fail_file(err, TD_ERR_IO, shown, 0, "cannot read the %s: %s", what, strerror(e));
    }
    fclose(f);
    buf[n] = '\0';
    for (i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)buf[i];
        if (binary_byte(ch)) {
            free(buf);
            return td_cr_fail_file(err, TD_ERR_PARSE, shown, line, "binary data (byte 0x%02x): a %s is text", ch, what);
        }
        if (ch == '\r' && buf[i + 1] != '\n') {
            /* libconfig ends a line (and a # comment) only at '\n': after a bare CR the settings
             * on the next "line" would be part of a comment, silently dropped (a CSV record's lines
             * end at '\n' too) */
            free(buf);
            return td_cr_fail_file(err, TD_ERR_PARSE, shown, line,
                                   "carriage return without a line feed (CR-only line endings are not "
                                   "supported; save the file with LF or CRLF line endings)");
        }
        if (ch == '\n')
            line++;
    }
    *text = buf;
    return TD_OK;
}

td_status td_cr_record_file(td_case *c, const char *path)
{
    size_t n = strlen(path);
    char **files = realloc(c->files, (size_t)(c->file_count + 1) * sizeof *files);
    if (!files)
        return TD_ERR_NOMEM;
    c->files = files;
    if (!(files[c->file_count] = malloc(n + 1)))
        return TD_ERR_NOMEM;
    memcpy(files[c->file_count], path, n + 1);
    c->file_count++;
    return TD_OK;
}

/* Record an integer literal libconfig would wrap. */
static td_status add_wrap(td_case_reader *r, const char *file, int line, int ordinal, const char *lit, size_t n)
{
    td_cr_wrap_site *s;
    if (r->wrap_count == r->wrap_cap) {
        int cap = r->wrap_cap ? 2 * r->wrap_cap : 4;
        td_cr_wrap_site *p = realloc(r->wraps, (size_t)cap * sizeof *p);
        if (!p)
            return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
        r->wraps = p;
        r->wrap_cap = cap;
    }
    s = &r->wraps[r->wrap_count];
    s->file = NULL;
    if (file) {
        s->file = malloc(strlen(file) + 1);
        if (!s->file)
            return td_cr_fail_file(r->err, TD_ERR_NOMEM, r->path_shown, 0, "out of memory");
        strcpy(s->file, file);
    }
    s->line = line;
    s->ordinal = ordinal;
    if (n >= sizeof s->literal)
        n = sizeof s->literal - 1;
    memcpy(s->literal, lit, n);
    s->literal[n] = '\0';
    r->wrap_count++;
    return TD_OK;
}

/* Does the number token tok[0..n) (no sign) overflow libconfig 1.5's 32-bit integers?
 * Floats (with '.', exponent) and 64-bit literals (suffix L) are fine. */
static int token_wraps(const char *tok, size_t n, int negative)
{
    size_t i, start;
    if (n > 2 && tok[0] == '0' && (tok[1] == 'x' || tok[1] == 'X')) {
        for (i = 2; i < n; i++)
            if (!isxdigit((unsigned char)tok[i]))
                return 0; /* 0x...L or malformed: libconfig's business */
        for (start = 2; start < n && tok[start] == '0'; start++)
            ;
        return n - start > 8;
    }
    for (i = 0; i < n; i++)
        if (!isdigit((unsigned char)tok[i]))
            return 0;
    for (start = 0; start + 1 < n && tok[start] == '0'; start++)
        ;
    if (n - start != 10)
        return n - start > 10;
    return strncmp(tok + start, negative ? "2147483648" : "2147483647", 10) > 0;
}

/* Length of the number token at s: digits, letters, '.', and a sign right after an exponent. */
static size_t number_length(const char *s)
{
    size_t n = 0;
    int hex = s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
    while (isalnum((unsigned char)s[n]) || s[n] == '.' || s[n] == '_' ||
           (!hex && n > 0 && (s[n] == '+' || s[n] == '-') && (s[n - 1] == 'e' || s[n - 1] == 'E')))
        n++;
    return n;
}

/* An "@include" line as libconfig 1.5 recognises it (at the start of a line, after blanks, then
 * blanks and a '"'): returns 1 and copies the name into `name`, 0 when the line is no include,
 * -1 when the name is not closed by a '"' on the same line (libconfig would take the name up to a
 * '"' on a later line), holds a backslash (an escape libconfig reads differently) or does not fit. */
static int include_line(const char *line, char *name, size_t n)
{
    const char *p = line, *q;
    while (*p == ' ' || *p == '\t')
        p++;
    if (strncmp(p, "@include", 8) != 0)
        return 0;
    p += 8;
    if (*p != ' ' && *p != '\t')
        return 0;
    while (*p == ' ' || *p == '\t')
        p++;
    if (*p != '"')
        return 0;
    for (q = p + 1; *q && *q != '"' && *q != '\n' && *q != '\\'; q++)
        ;
    if (*q != '"' || (size_t)(q - p - 1) >= n)
        return -1;
    memcpy(name, p + 1, (size_t)(q - p - 1));
    name[q - p - 1] = '\0';
    return 1;
}

/* Refuse an @include that would pass the bounds of case.h: nesting depth, number of included
 * files, and bytes read. Without them a file that includes itself k times is expanded k^10 times
 * (libconfig's own nesting limit) before anything is reported. */
static td_status include_bounds(td_case_reader *r, const char *file, int line_no, int depth)
{
    char including[4096];
    td_cr_file_shown(r, file, including, sizeof including);
    if (depth >= TD_CASE_MAX_INCLUDE_DEPTH)
        return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no,
                               "@include nested more than %d deep (does a file include itself?)",
                               TD_CASE_MAX_INCLUDE_DEPTH);
    if (r->includes >= TD_CASE_MAX_INCLUDES)
        return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no, "more than %d @include files in one case",
                               TD_CASE_MAX_INCLUDES);
    return TD_OK;
}

static td_status too_many_bytes(td_case_reader *r, const char *including, int line_no)
{
    return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no,
                           "the case and its @include files exceed %ld bytes in all", (long)TD_CASE_MAX_TOTAL_SIZE);
}

/* Expand one @include (on line `line_no` of `file`): append the included file's text between
 * marker comments. An include that cannot be read is reported here, before libconfig would open
 * it: libconfig 1.5 would block on a FIFO and misreport a directory. */
static td_status expand_include(td_case_reader *r, const char *file, int line_no, const char *name, int depth,
                                td_text *out)
{
    char path[4096], shown[4096], including[4096], quoted[256];
    char *text = NULL;
    struct stat sb;
    td_error ierr;
    td_status st = include_bounds(r, file, line_no, depth);
    if (st != TD_OK)
        return st;
    td_cr_file_shown(r, file, including, sizeof including);
    td_cr_printable(name, quoted, sizeof quoted);
    if (name[0] == '/')
        return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no,
                               "cannot open include file \"%.200s\" (absolute @include paths are not supported: "
                               "libconfig 1.5 reads them relative to %.200s)",
                               quoted, r->dir_shown);
    if (snprintf(path, sizeof path, "%s/%s", r->dir, name) >= (int)sizeof path)
        return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no,
                               "include file \"%.200s\": the path is longer than %d characters", quoted,
                               (int)sizeof path - 1);
    td_cr_file_shown(r, name, shown, sizeof shown);
    if (stat(path, &sb) == 0 && S_ISREG(sb.st_mode) &&
        (unsigned long long)sb.st_size > (unsigned long long)TD_CASE_MAX_TOTAL_SIZE - r->bytes)
        return too_many_bytes(r, including, line_no); /* refused before reading a byte of it */
    st = td_cr_read_file("case file", shown, path, &text, &ierr);
    if (st == TD_ERR_IO)
        return td_cr_fail_file(r->err, TD_ERR_PARSE, including, line_no,
                               "cannot open include file \"%.200s\" (%.200s; @include paths are relative to %.200s)",
                               quoted, ierr.message, r->dir_shown);
    if (st != TD_OK) {
        if (r->err)
            *r->err = ierr;
        return st;
    }
    r->includes++;
    if (td_cr_record_file(r->c, path) != TD_OK) {
        free(text);
        return td_error_set(r->err, TD_ERR_NOMEM, "%s:%d: out of memory", including, line_no);
    }
    r->bytes += strlen(text);
    if (r->bytes > (size_t)TD_CASE_MAX_TOTAL_SIZE) { /* it grew after stat */
        free(text);
        return too_many_bytes(r, including, line_no);
    }
    td_text_printf(out, "# >>> @include \"%s\" (%s)\n", quoted, shown);
    st = td_cr_expand(r, text, name, depth + 1, out);
    if (out->len > 0 && out->data[out->len - 1] != '\n')
        td_text_append(out, "\n", 1);
    td_text_printf(out, "# <<< end of \"%s\"\n", quoted);
    free(text);
    return st;
}

typedef enum scan_state { SCAN_CODE, SCAN_LINE_COMMENT, SCAN_BLOCK_COMMENT, SCAN_STRING } scan_state;

/* libconfig's boolean literals (case-insensitive), the only names that are values, not keys. */
static int boolean_word(const char *p, size_t n)
{
    return (n == 4 && strncasecmp(p, "true", 4) == 0) || (n == 5 && strncasecmp(p, "false", 5) == 0);
}

/* Count one more setting; refuse past TD_CASE_MAX_SETTINGS. */
static td_status count_setting(td_case_reader *r, const char *file, int line)
{
    char shown[4096];
    if (++r->shape.settings <= TD_CASE_MAX_SETTINGS)
        return TD_OK;
    td_cr_file_shown(r, file, shown, sizeof shown);
    return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, line,
                           "more than %d settings and list or array entries in one case (the limit of "
                           "docs/case-format.md)",
                           TD_CASE_MAX_SETTINGS);
}

/* In a group (or the root), where names are keys; else in a list or array, where each value is
 * an entry. */
static int in_group(const td_cr_shape *sh)
{
    return sh->depth == 0 || sh->open[sh->depth - 1] == '{';
}

/* A key `name` (n bytes) of the innermost group: libconfig compares it with each earlier key. */
static td_status count_key(td_case_reader *r, const char *file, int line, const char *name, size_t n)
{
    td_cr_shape *sh = &r->shape;
    char shown[4096], key[64];
    if (sh->keys[sh->depth] >= TD_CASE_MAX_GROUP_KEYS) {
        td_cr_file_shown(r, file, shown, sizeof shown);
        snprintf(key, sizeof key, "%.*s", (int)(n < 40 ? n : 40), name);
        return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, line, "%s: more than %d keys in one group", key,
                               TD_CASE_MAX_GROUP_KEYS);
    }
    sh->name_compares += (unsigned long long)sh->keys[sh->depth];
    sh->keys[sh->depth]++;
    return count_setting(r, file, line);
}

/* An opening bracket: an entry when inside a list or array, and one level deeper. */
static td_status open_bracket(td_case_reader *r, const char *file, int line, char ch)
{
    td_cr_shape *sh = &r->shape;
    char shown[4096];
    td_status st = in_group(sh) ? TD_OK : count_setting(r, file, line);
    if (st != TD_OK)
        return st;
    if (sh->depth >= TD_CASE_MAX_NESTING) {
        td_cr_file_shown(r, file, shown, sizeof shown);
        return td_cr_fail_file(r->err, TD_ERR_PARSE, shown, line, "groups, lists and arrays nested more than %d deep",
                               TD_CASE_MAX_NESTING);
    }
    sh->open[sh->depth++] = ch;
    sh->keys[sh->depth] = 0;
    return TD_OK;
}

/* Account for the code token at p (n bytes) in the shape of the case. */
static td_status shape_token(td_case_reader *r, const char *file, int line, const char *p, size_t n)
{
    td_cr_shape *sh = &r->shape;
    if (*p == '{' || *p == '(' || *p == '[')
        return open_bracket(r, file, line, *p);
    if (*p == '}' || *p == ')' || *p == ']') {
        if (sh->depth > 0) /* an unbalanced one is libconfig's syntax error */
            sh->depth--;
        return TD_OK;
    }
    if (in_group(sh))
        return (isalpha((unsigned char)*p) || *p == '_' || *p == '*') && !boolean_word(p, n)
                   ? count_key(r, file, line, p, n)
                   : TD_OK;
    return count_setting(r, file, line);
}

/* The scan of one file's text by td_cr_expand: where it is, and what it is inside. */
typedef struct text_scan {
    td_case_reader *r;
    const char *text; /* the whole text (to see the sign before a number) */
    const char *file; /* as libconfig calls it; NULL for the main file */
    int depth;        /* @include nesting of this file */
    td_text *out;
    const char *p;          /* the next byte */
    const char *line_start; /* where the current line starts */
    scan_state state;
    int line;
    int comment_line;    /* where the open block comment started */
    int numbers_on_line; /* number tokens so far on this line (td_cr_wrap_site.ordinal) */
} text_scan;

/* Copy n bytes to the output and step past them. */
static void scan_copy(text_scan *s, size_t n)
{
    td_text_append(s->out, s->p, n);
    s->p += n;
}

/* Fail at the current line of the file being scanned. */
static td_status scan_fail(const text_scan *s, int line, const char *message)
{
    char shown[4096];
    td_cr_file_shown(s->r, s->file, shown, sizeof shown);
    return td_cr_fail_file(s->r->err, TD_ERR_PARSE, shown, line, "%s", message);
}

/* At the start of a line of code: expand an @include line in place of the line (*done = 1), or
 * leave a line that is no include to the scan (*done = 0). */
static td_status scan_include(text_scan *s, int *done)
{
    char name[1024], shown[4096];
    const char *end;
    td_status st;
    int inc = include_line(s->p, name, sizeof name);
    *done = inc != 0;
    if (inc < 0) {
        td_cr_file_shown(s->r, s->file, shown, sizeof shown);
        return td_cr_fail_file(s->r->err, TD_ERR_PARSE, shown, s->line,
                               "@include: the file name must be closed by '\"' on the same line, without "
                               "backslashes, and be shorter than %d bytes",
                               (int)sizeof name);
    }
    if (!inc)
        return TD_OK;
    end = strchr(s->p, '\n');
    st = expand_include(s->r, s->file, s->line, name, s->depth, s->out);
    if (st != TD_OK)
        return st;
    s->p += end ? (size_t)(end - s->p + 1) : strlen(s->p);
    s->line_start = s->p;
    s->line++;
    return TD_OK;
}

/* A line feed: ends a # or // comment. */
static void scan_newline(text_scan *s)
{
    scan_copy(s, 1);
    s->line_start = s->p;
    s->line++;
    s->numbers_on_line = 0;
    if (s->state == SCAN_LINE_COMMENT)
        s->state = SCAN_CODE;
}

/* Inside a block comment: bytes to copy, 2 for the closing star-slash. */
static size_t block_comment_bytes(text_scan *s)
{
    if (s->p[0] == '*' && s->p[1] == '/') {
        s->state = SCAN_CODE;
        return 2;
    }
    return 1;
}

/* Inside a string: bytes to copy, 2 for an escape (so an escaped '"' does not end it). */
static size_t string_bytes(text_scan *s)
{
    if (s->p[0] == '\\' && s->p[1] != '\0' && s->p[1] != '\n')
        return 2;
    if (*s->p == '"')
        s->state = SCAN_CODE;
    return 1;
}

/* A name or true/false, skipped whole so that digits inside it are not numbers; *n: its length. */
static td_status name_token(text_scan *s, size_t *n)
{
    const char *p = s->p;
    size_t len = 1;
    while (isalnum((unsigned char)p[len]) || p[len] == '_' || p[len] == '*' || p[len] == '-')
        len++;
    *n = len;
    return shape_token(s->r, s->file, s->line, p, len);
}

/* A number: recorded when libconfig would wrap it; *n: its length. */
static td_status number_token(text_scan *s, size_t *n)
{
    const char *p = s->p;
    size_t len = number_length(p);
    int negative = p > s->text && p[-1] == '-';
    td_status st;
    if (token_wraps(p, len, negative)) {
        st = add_wrap(s->r, s->file, s->line, s->numbers_on_line, p, len);
        if (st != TD_OK)
            return st;
    }
    s->numbers_on_line++;
    *n = len;
    return shape_token(s->r, s->file, s->line, p, len);
}

/* In code: the token that starts here (a comment or string opening, a name, a number, a bracket,
 * any other byte); *n: the bytes to copy. */
static td_status code_token(text_scan *s, size_t *n)
{
    const char *p = s->p;
    *n = 1;
    if (*p == '#' || (p[0] == '/' && p[1] == '/')) {
        s->state = SCAN_LINE_COMMENT;
    } else if (p[0] == '/' && p[1] == '*') {
        s->state = SCAN_BLOCK_COMMENT;
        s->comment_line = s->line;
        *n = 2;
    } else if (*p == '"') {
        s->state = SCAN_STRING;
        return shape_token(s->r, s->file, s->line, p, 1);
    } else if (isalpha((unsigned char)*p) || *p == '_' || *p == '*') {
        return name_token(s, n);
    } else if (isdigit((unsigned char)*p) || (*p == '.' && isdigit((unsigned char)p[1]))) {
        return number_token(s, n);
    } else if (strchr("{}()[]", *p)) {
        return shape_token(s->r, s->file, s->line, p, 1);
    }
    return TD_OK;
}

/* One step of the scan: an @include line, a line feed, or the next byte or token in its state. */
static td_status scan_step(text_scan *s)
{
    size_t n = 1;
    int done = 0;
    td_status st = TD_OK;
    if (s->p == s->line_start && s->state == SCAN_CODE) {
        st = scan_include(s, &done);
        if (st != TD_OK || done)
            return st;
    }
    if (*s->p == '\n') {
        scan_newline(s);
        return TD_OK;
    }
    switch (s->state) {
    case SCAN_LINE_COMMENT: break;
    case SCAN_BLOCK_COMMENT: n = block_comment_bytes(s); break;
    case SCAN_STRING: n = string_bytes(s); break;
    case SCAN_CODE: st = code_token(s, &n); break;
    }
    if (st == TD_OK)
        scan_copy(s, n);
    return st;
}

/* At the end of the text: what libconfig would get wrong there, and a failed allocation. */
static td_status scan_end(const text_scan *s)
{
    if (s->state == SCAN_BLOCK_COMMENT)
        return scan_fail(s, s->comment_line,
                         "unterminated /* comment (libconfig would silently ignore the rest of the file)");
    if (s->state == SCAN_LINE_COMMENT && s->file)
        /* libconfig 1.5 reads an included file itself and rejects a last-line comment without a
         * final newline as "syntax error"; the main file gets the newline appended (case.c) */
        return scan_fail(s, s->line,
                         "an included file must end with a newline after its last comment (libconfig 1.5 "
                         "cannot read it otherwise)");
    if (s->out->failed)
        return td_cr_fail_file(s->r->err, TD_ERR_NOMEM, s->r->path_shown, 0, "out of memory");
    return TD_OK;
}

td_status td_cr_expand(td_case_reader *r, const char *text, const char *file, int depth, td_text *out)
{
    text_scan s;
    td_status st = TD_OK;
    s.r = r;
    s.text = text;
    s.file = file;
    s.depth = depth;
    s.out = out;
    s.p = s.line_start = text;
    s.state = SCAN_CODE;
    s.line = 1;
    s.comment_line = 0;
    s.numbers_on_line = 0;
    while (*s.p && st == TD_OK)
        st = scan_step(&s);
    return st == TD_OK ? scan_end(&s) : st;
}

int td_cr_value_wraps(const char *text, char *literal, size_t n)
{
    const char *p = text;
    int in_string = 0;
    for (; *p; p++) {
        if (in_string) {
            if (*p == '\\' && p[1])
                p++;
            else if (*p == '"')
                in_string = 0;
        } else if (*p == '"') {
            in_string = 1;
        } else if (isalpha((unsigned char)*p) || *p == '_') {
            while (isalnum((unsigned char)p[1]) || p[1] == '_' || p[1] == '-')
                p++;
        } else if (isdigit((unsigned char)*p)) {
            size_t len = number_length(p);
            if (token_wraps(p, len, p > text && p[-1] == '-')) {
                size_t k = len < n ? len : n - 1;
                memcpy(literal, p, k);
                literal[k] = '\0';
                return 1;
            }
            p += len - 1;
        }
    }
    return 0;
}
