/* io/io_error.c: io_name_error (io/text_reader.h), the file name put in
 * front of an error recorded by a layer below that does not know it. */
#include "text_reader.h"

#include <stdio.h>

glpgp_status io_name_error(const char *path, glpgp_status st)
{
    char msg[1024];
    snprintf(msg, sizeof msg, "%s", glpgp_error_message());
    glpgp_error_clear();
    return glpgp_error_set(__FILE__, __LINE__, st, "%s: %s", path, msg);
}
