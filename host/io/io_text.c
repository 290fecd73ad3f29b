/* io/io_text.c: the io layer's helpers over the core's text reader
 * (io/text_reader.h): the file name put in front of an error recorded by a
 * layer below that does not know it, and an OBJ face corner. */
#include "text_reader.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

glpgp_status io_name_error(const char *path, glpgp_status st)
{
    char msg[1024];
    snprintf(msg, sizeof msg, "%s", glpgp_error_message());
    glpgp_error_clear();
    return glpgp_error_set(__FILE__, __LINE__, st, "%s: %s", path, msg);
}

glpgp_status obj_corner(const text_reader *tr, char **s, long long *idx)
{
    *s = text_skip_ws(*s);
    *idx = 0;
    if (**s == '\0') return GLPGP_OK;
    char *tok = *s, *e;
    errno = 0;
    long long v = strtoll(tok, &e, 10);
    if (e == tok || errno == ERANGE || (*e && *e != '/' && !isspace((unsigned char)*e)))
        return text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed face index '%.40s'", tok);
    /* optional /vt/vn parts: digits, signs and slashes only */
    while (*e && !isspace((unsigned char)*e)) {
        if (!(isdigit((unsigned char)*e) || *e == '/' || *e == '-'))
            return text_error(tr, GLPGP_ERR_FORMAT, 0, "malformed face corner '%.40s'", tok);
        e++;
    }
    if (v == 0) return text_error(tr, GLPGP_ERR_FORMAT, 0, "face index 0 is invalid (OBJ indices start at 1)");
    *s = e;
    *idx = v;
    return GLPGP_OK;
}
