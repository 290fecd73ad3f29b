/* io/text_reader.h: the io layer's use of the core's line reader
 * (glpgp/internal/text.h) and the io layer's file-name prefix for errors.
 * Private to the io layer. */
#ifndef GLPGP_IO_TEXT_READER_H
#define GLPGP_IO_TEXT_READER_H

#include "glpgp/internal/text.h"

/* Put "PATH: " in front of the recorded error (for errors of
 * glpgp_mesh_create, which does not know the file). Returns st. */
glpgp_status io_name_error(const char *path, glpgp_status st);

#endif
