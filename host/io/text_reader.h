/* io/text_reader.h: the io layer's use of the core's line reader
 * (glpgp/internal/text.h) and the io layer's file-name prefix for errors.
 * Private to the io layer. */
#ifndef GLPGP_IO_TEXT_READER_H
#define GLPGP_IO_TEXT_READER_H

#include "glpgp/internal/text.h"

/* Put "PATH: " in front of the recorded error (for errors of
 * glpgp_mesh_create, which does not know the file). Returns st. */
glpgp_status io_name_error(const char *path, glpgp_status st);

/* The next corner of an OBJ face line at *s: its index (1-based, or
 * negative: relative to the vertices defined so far) in *idx, 0 at the end
 * of the line; "/vt/vn" parts skipped; *s advanced. GLPGP_ERR_FORMAT (with
 * the line) on a malformed corner or index 0. */
glpgp_status obj_corner(const text_reader *tr, char **s, long long *idx);

#endif
