#!/bin/bash
# cli_sizefield.sh: the local size field on the command line:
#  - a rectangle 8 x 2 meshed with x edges graded 40x (0.019 .. 0.74) at
#    h = 0.6 (1.5 mean edges): --size-field none refuses it (usage error,
#    h below 2 mean edges, as before size fields); the default (auto) refines
#    the coarse part (the summary says so) and gives a valid all-quad mesh;
#    with --no-refine (at h = 2.5) the local size is limited to what the
#    input resolves, with a warning saying so;
#  - --size-field FILE: a good file is used (exit 0), a file with a wrong
#    line count or a non-positive size is one error line naming the file;
#  - --size-field none and the default give the same result file on a domain
#    without thin walls (the field is uniform there: bit for bit).
. "$(dirname "$0")/lib.sh" "$@"

# graded grid: 40 columns (x_i = 8 (q^i - 1) / (q^40 - 1), q = 40^(1/39)), 4 rows
awk 'BEGIN {
    q = exp(log(40) / 39); n = 40; m = 4;
    for (j = 0; j <= m; j++) for (i = 0; i <= n; i++) printf "v %.17g %.17g\n", 8 * (q^i - 1) / (q^n - 1), 2 * j / m;
    for (j = 0; j < m; j++) for (i = 0; i < n; i++) {
        a = j * (n + 1) + i + 1; b = a + 1; c = a + n + 1; d = c + 1;
        printf "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c
    } }' >graded.obj

run_fail "graded 40x, none" 2 "mean edge" solve graded.obj --size 0.6 --size-field none --backend reference
run_ok "graded 40x, auto" solve graded.obj --size 0.6 --backend reference --quads q.obj
expect_out "refined +[0-9]+ -> [0-9]+ vertices" "graded 40x, auto: refinement reported"
expect_out "valid +yes" "graded 40x, auto: valid quad mesh"
expect_out "quads +[0-9]+ quads, 0 other faces" "graded 40x, auto: all quads"
run_ok "graded 40x, --no-refine" solve graded.obj --size 2.5 --no-refine --backend reference
expect_err "local size is limited by the mesh.*refine" "graded 40x, --no-refine: the limit is reported"

# size files on the built-in square (16 vertices at :16)
run_ok "square" solve shape:square:16 --backend reference -o none.vtk --size-field none
nv=$(awk '/^POINTS/ {print $2; exit}' none.vtk)
awk -v n="$nv" 'BEGIN { for (i = 0; i < n; i++) print 5 }' >good.txt
awk -v n="$nv" 'BEGIN { for (i = 1; i < n; i++) print 5 }' >short.txt
awk -v n="$nv" 'BEGIN { print -1; for (i = 1; i < n; i++) print 5 }' >neg.txt
run_ok "size file" solve shape:square:16 --backend reference --size-field good.txt
run_fail "size file, one line short" 1 "short.txt.*size lines for" solve shape:square:16 --backend reference \
    --quiet --size-field short.txt
one_error_line "size file, one line short"
run_fail "size file, negative size" 1 "neg.txt:1: sizes must be positive" solve shape:square:16 --backend reference \
    --quiet --size-field neg.txt
one_error_line "size file, negative size"

# uniform field: default (auto) = none, bit for bit, on a domain without thin
# walls whose chords are within the budget (h = 0.16: the disk's chords lose
# h^2 / 6 = 0.43% of its area, under --size-chord-area 0.5%; the input fine
# enough for h / 4, so not refined)
run_ok "disk, none" solve shape:disk:6000 --size 0.16 --backend reference -o d_none.vtk --size-field none
run_ok "disk, default" solve shape:disk:6000 --size 0.16 --backend reference -o d_auto.vtk
cmp -s d_none.vtk d_auto.vtk || fail "disk: default (auto) and none differ on a domain without thin walls"
# at its default size (0.22: 0.8%) the chord budget makes the size local
run_ok "disk, default size" solve shape:disk:3000 --backend reference -o d_def.vtk
run_ok "disk, default size, no chord budget" solve shape:disk:3000 --backend reference -o d_def0.vtk \
    --size-chord-area 0 --size-chord-depth 0
run_ok "disk, default size, none" solve shape:disk:3000 --backend reference -o d_defn.vtk --size-field none
cmp -s d_def0.vtk d_defn.vtk || fail "disk: auto without the chord budget and none differ"
cmp -s d_def.vtk d_defn.vtk && fail "disk at its default size: the chord budget changed nothing"
finish
