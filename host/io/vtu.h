/* io/vtu.h: VTK XML UnstructuredGrid (.vtu) with every array in one
 * appended raw section: the generic writer (arrays produced tuple by tuple
 * through a callback, optionally zlib-compressed) and the reader of such
 * files (header parsed from the text lines, arrays read in offset order, one
 * pass). The result and quad-mesh writers and the result reader map their
 * data onto it. Private to the io layer. */
#ifndef GLPGP_IO_VTU_H
#define GLPGP_IO_VTU_H

#include "glpgp/status.h"
#include "text_reader.h"

#include <stddef.h>
#include <stdio.h>

enum { VTU_FIELD = 0, VTU_POINTDATA, VTU_CELLDATA, VTU_POINTS, VTU_CELLS, VTU_NSECTIONS };

/* Writes tuples [first, first + count) of an array into out. */
typedef void (*vtu_fill_fn)(const void *ctx, size_t first, size_t count, void *out);

typedef struct vtu_array {
    int section;      /* VTU_* */
    const char *name; /* Name attribute */
    const char *type; /* "Float64", "Int32", "Int8", "UInt8" */
    int elsize;       /* bytes per component */
    int ncomp;
    size_t ntuples;
    vtu_fill_fn fill;
    const void *ctx;
} vtu_array;

/* Write the file to f (a stream of an output set: it must support fseek).
 * comment goes into an XML comment. level 0: raw, 1..9: zlib (raw without
 * zlib). Stream errors surface at the set's commit; GLPGP_ERR_IO here only
 * for a failed seek, GLPGP_ERR_NOMEM. */
glpgp_status vtu_write(FILE *f, const char *comment, size_t npoints, size_t ncells, const vtu_array *a,
                       int na, int level);

/* ---- reading ------------------------------------------------------------------ */

#define VTU_MAX_ARRAYS 64

typedef struct vtu_in_array {
    int section;
    char name[64];
    char type[16];
    int elsize;
    int ncomp;
    long long ntuples; /* NumberOfTuples (FieldData), else from the piece */
    long long offset;
} vtu_in_array;

typedef struct vtu_reader {
    text_reader *tr;  /* positioned after the first line ("<?xml ..." or "<VTKFile ...") */
    int swap;         /* file byte order differs from the host's */
    int header64;     /* header_type UInt64 (else UInt32) */
    int compressed;
    long long npoints, ncells;
    vtu_in_array arrays[VTU_MAX_ARRAYS];
    int narrays;
    long long pos;    /* bytes of appended data consumed */
} vtu_reader;

/* Parse the XML header up to the start of the appended data. first_line is
 * the first line already taken from tr. Checks the attributes this reader
 * needs (UnstructuredGrid, one piece, appended raw data, known types,
 * counts within GLPGP_IO_MAX_ITEMS). */
glpgp_status vtu_read_header(vtu_reader *v, text_reader *tr, const char *first_line);

/* The array of a section with a name (name NULL: the section's first array),
 * or NULL. */
const vtu_in_array *vtu_find(const vtu_reader *v, int section, const char *name);

/* Read array a (arrays must be read in increasing offset order; skipped ones
 * are passed over) holding exactly `count` components: *out receives
 * `count` values converted to double (out_d) or long long (out_ll; exactly one
 * of them is non-NULL); non-finite doubles are an error. Memory grows with
 * the data read (compressed blocks: at most 1100 times their size). */
glpgp_status vtu_read_array(vtu_reader *v, const vtu_in_array *a, size_t count, double **out_d,
                            long long **out_ll);

#endif
