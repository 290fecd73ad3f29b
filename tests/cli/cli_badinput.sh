#!/usr/bin/env bash
# cli_badinput.sh: every bad-input and fault class of issue 15, class by
# class, through the CLI. Usage: bash cli_badinput.sh <path-to-glpgp> <data-dir>
# Each case checks: the exit code (1 failure, 2 usage error), exactly one
# message line (one_error_line) that names the file or option and matches the
# problem, no output file and no temporary left, and that the work stayed
# bounded: under 5 s of CPU time (user + sys: a loaded machine stretches the
# wall time, not the work) and 300 MiB of memory (/usr/bin/time -f '%U %S %M'),
# and under 120 s of wall time (a hang; the only check without /usr/bin/time). The inputs are written here
# (printf, awk; PNG files with python3 when it is there).
# Classes: quad-mesh MSH 4.1 block counts 2^61 and LONG_MAX; MSH 2.2 quads
# from a pipe; a 177-byte MSH with node tags up to 1e8; VTK results with a
# second POINTS section, a nan oscillator value, 1e9 declared cells, a
# recorded h of 1e-300 or 1e300 (extract); field files with 1e200 / 1e-200
# components (accepted) and a 600-character line (error on that line); a
# folded mesh, a face repeating a vertex; --quads in a missing directory
# (refused before the solve); --cg-max 1 (warns); --size 1e-300 / 1e300;
# --max-elements on files, shapes and generate; with OpenImageIO and Gmsh:
# the mask that made Gmsh 4.8 abort (meshes now), a Gmsh child that aborts
# (GLPGP_TEST_GMSH_FAULT=abort: one line, exit 1), a --mesh-size far below
# the pixel size (refused before Gmsh), a 20000 x 20000 PNG of 400 kB
# (refused from its header), truncated / corrupt PNGs (no libpng line),
# --image-size beyond --max-pixels, SIGTERM while Gmsh runs (exit 143, the
# Gmsh process goes too). Interrupts during a solve and full disks are
# covered by cli_errors.sh and tests/io/test_output_set.c.
. "$(dirname "$0")/lib.sh" "$@"

TIME_BIN=/usr/bin/time
[ -x "$TIME_BIN" ] || TIME_BIN=
MAX_S=5      # CPU seconds
MAX_WALL=120 # wall seconds
MAX_KB=$((300 * 1024))

# measured WANT WHAT ARGS...: run with time and memory measured (stats.txt)
measured() {
    local want=$1 what=$2
    shift 2
    runs=$((runs + 1))
    local t0 t1 rc
    t0=$(date +%s.%N)
    if [ -n "$TIME_BIN" ]; then
        "$TIME_BIN" -o stats.txt -f '%U %S %M' "$GLPGP" "$@" >out.txt 2>err.txt </dev/null
    else
        "$GLPGP" "$@" >out.txt 2>err.txt </dev/null
    fi
    rc=$?
    t1=$(date +%s.%N)
    [ "$rc" -eq "$want" ] || fail "$what: expected exit $want, got $rc (stderr: $(head -c 400 err.txt))"
    local secs cpu kb
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
    cpu=$([ -n "$TIME_BIN" ] && tail -n 1 stats.txt | awk '{ printf "%.2f", $1 + $2 }' || echo 0)
    kb=$([ -n "$TIME_BIN" ] && tail -n 1 stats.txt | awk '{ print $3 }' || echo 0)
    awk -v s="$secs" -v m="$MAX_WALL" 'BEGIN { exit !(s < m) }' || fail "$what: took $secs s of wall time (limit $MAX_WALL s)"
    awk -v s="$cpu" -v m="$MAX_S" 'BEGIN { exit !(s < m) }' || fail "$what: took $cpu s of CPU time (limit $MAX_S s)"
    [ "${kb:-0}" -lt "$MAX_KB" ] || fail "$what: used $kb KiB (limit $MAX_KB KiB)"
    printf '  %-44s exit %d  %5s s wall  %5s s cpu  %6s MiB\n' "$what" "$rc" "$secs" "$cpu" "$((${kb:-0} / 1024))"
}

# bad WANT REGEX WHAT ARGS...: a failing run with one message line matching REGEX
bad() {
    local want=$1 pat=$2 what=$3
    shift 3
    measured "$want" "$what" "$@"
    one_error_line "$what"
    expect_err "$pat" "$what"
    no_tmp "$what"
    for f in o.vtk o.json o.msh o.obj o.png q.obj; do
        [ ! -e "$f" ] || { fail "$what: output $f left behind"; rm -f "$f"; }
    done
}

echo "glpgp: $("$GLPGP" --version)"

# ---- meshes ----------------------------------------------------------------
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 2305843009213693952\n1\n$EndNodes\n' >in_1.msh
bad 1 'in_1\.msh:[0-9]+: .*node' "quality: node block count 2^61" quality in_1.msh
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 9223372036854775807\n1\n$EndNodes\n' >in_2.msh
bad 1 'in_2\.msh:[0-9]+: .*node' "quality: node block count LONG_MAX" quality in_2.msh
# node tags up to 1e8 with 3 nodes: a hash, not an array of 1e8 entries
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 100000000\n2 1 0 3\n1\n50000000\n100000000\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 50000000 100000000\n$EndElements\n' >in_3.msh
# read in bounded memory; one triangle is not a quad mesh: reported invalid (exit 3)
measured 3 "quality: 177-byte MSH, tags up to 1e8" quality in_3.msh
# MSH 2.2 quads from a pipe (one pass, no seeking)
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0\n$EndNodes\n$Elements\n2\n1 3 2 0 1 1 2 5 4\n2 3 2 0 1 2 3 6 5\n$EndElements\n' >in_4.msh
runs=$((runs + 1))
"$GLPGP" quality /dev/stdin <in_4.msh >out.txt 2>err.txt || fail "quality from a pipe: exit $? ($(head -c 300 err.txt))"
grep -q "2 quads" out.txt || fail "quality from a pipe: $(head -3 out.txt)"

printf 'v 0 0\nv 2 0\nv 1 1\nv 1 0.5\nf 1 2 3\nf 1 2 4\n' >in_5.obj
bad 1 'in_5\.obj: .*fold' "solve: folded mesh" solve in_5.obj -o o.vtk --stats o.json
printf 'v 0 0\nv 1 0\nv 0 1\nf 1 1 2\n' >in_6.obj
bad 1 'in_6\.obj:4: .*vertex 1 more than once' "solve: face repeating a vertex" solve in_6.obj -o o.vtk
"$GLPGP" generate square --vertices 400 -o sq.obj >/dev/null || fail "generate sq.obj"
bad 1 'sq\.obj: [0-9]+ triangles: more than the limit of 100 \(--max-elements\)' \
    "solve: file above --max-elements" solve sq.obj --max-elements 100 -o o.vtk
bad 1 'shape:disk:20000000: about 40000000 triangles.*--max-elements' \
    "solve: shape above --max-elements" solve shape:disk:20000000 -o o.vtk
bad 1 'about 100000000 triangles.*--max-elements' "generate above --max-elements" \
    generate disk --vertices 50000000 -o o.obj
bad 2 'max-elements' "--max-elements 0" solve sq.obj --max-elements 0

# ---- options ---------------------------------------------------------------
bad 1 'nodir' "solve --quads in a missing directory" solve sq.obj --quads nodir/x.obj -o o.vtk
bad 2 '--size.*mean edge' "solve --size 1e-300" solve sq.obj --size 1e-300 -o o.vtk
bad 2 '--size.*diameter' "solve --size 1e300" solve sq.obj --size 1e300 -o o.vtk
# (--newton-max 10: the CG cap is the point; 50 capped Newton steps per level took 3.6 s of the
# 5 s CPU bound on 2 cores, 5.0 s with another build beside it)
measured 0 "solve --cg-max 1 (warns)" solve sq.obj --cg-max 1 --newton-max 10 --backend reference -o o.vtk
grep -q "warning: u: CG stopped at its cap of 1 iterations" err.txt ||
    fail "--cg-max 1: no CG cap warning: $(head -c 300 err.txt)"
grep -q "warning: v: CG stopped at its cap" err.txt || fail "--cg-max 1: no warning for v"
[ "$(grep -c 'CG stopped at its cap of 1 iterations in' err.txt)" -eq 2 ] ||
    fail "--cg-max 1: expected one cap warning per oscillator"
rm -f o.vtk

# ---- field files -----------------------------------------------------------
"$GLPGP" generate square --vertices 16 -o sq16.obj >/dev/null
awk 'BEGIN { print "3e200 4e200"; for (i = 0; i < 15; i++) print "1e-200 0" }' >f_big.txt
measured 0 "solve --field: 1e200 and 1e-200 components" solve sq16.obj --field f_big.txt --backend reference -o o.vtk
if [ -s o.vtk ]; then # the stored field: (0.6, 0.8) and (1, 0)
    awk '/^VECTORS field_u/ { getline; print; getline; print; exit }' o.vtk >fu.txt
    awk 'NR == 1 { ok = ($1 > 0.5999999 && $1 < 0.6000001 && $2 > 0.7999999 && $2 < 0.8000001) }
         NR == 2 { ok = ok && ($1 == 1 && $2 == 0) } END { exit !ok }' fu.txt ||
        fail "field 1e200 / 1e-200: stored $(tr '\n' ' ' <fu.txt)"
fi
rm -f o.vtk
awk 'BEGIN { print "1 0"; s = "1 0 "; for (i = 0; i < 596; i++) s = s "x"; print s;
             for (i = 0; i < 14; i++) print "1 0" }' >f_long.txt
bad 1 'f_long\.txt:2: ' "solve --field: 600-character line" solve sq16.obj --field f_long.txt -o o.vtk

# ---- results (extract, render) ---------------------------------------------
"$GLPGP" solve sq16.obj --backend reference --size 0.9 -o r.vtk --quiet >/dev/null 2>&1 || fail "solve r.vtk"
if [ -s r.vtk ]; then
    awk '/^CELLS/ && !done { print "POINTS 2 double"; print "0 0 0"; print "1 0 0"; done = 1 } { print }' r.vtk >r_points.vtk
    bad 1 'r_points\.vtk:[0-9]+: second POINTS' "extract: second POINTS section" extract r_points.vtk --quads q.obj
    awk '/^SCALARS z_u/ { print; getline; print; getline; print "nan 0"; next } { print }' r.vtk >r_nan.vtk
    bad 1 'r_nan\.vtk:[0-9]+: .*finite' "extract: nan oscillator value" extract r_nan.vtk --quads q.obj
    sed 's/^CELLS .*/CELLS 1000000000 4000000000/' r.vtk >r_cells.vtk
    bad 1 'r_cells\.vtk:[0-9]+: 1000000000 cells' "extract: 1e9 cells declared" extract r_cells.vtk --quads q.obj
    sed '2s/ h [0-9.e+-]*/ h 1e-300/' r.vtk >r_h.vtk
    bad 1 'r_h\.vtk: the recorded size h = 1e-300' "extract: recorded h = 1e-300" extract r_h.vtk --quads q.obj
    sed '2s/ h [0-9.e+-]*/ h 1e300/' r.vtk >r_H.vtk
    bad 1 'r_H\.vtk: the recorded size h = 1e\+300' "extract: recorded h = 1e300" extract r_H.vtk --quads q.obj
    bad 2 '--size.*mean edge' "extract --size 1e-300" extract r.vtk --size 1e-300 --quads q.obj
    bad 1 'r\.vtk: [0-9]+ triangles: more than the limit of 10' "extract above --max-elements" \
        extract r.vtk --max-elements 10 --quads q.obj
fi

# ---- images and Gmsh (skipped without OpenImageIO and Gmsh) ------------------
if ! "$GLPGP" --version | grep -q "OpenImageIO: yes; Gmsh: yes"; then
    echo "  (image cases skipped: $("$GLPGP" --version))"
    finish
fi
# the 12 x 18 mask on which Gmsh 4.8 aborted (exit 134) with --simplify 2 --min-area 0.5
{
    printf 'P2\n12 18\n255\n'
    for r in 000000111011 000100000000 101000100101 111111100011 111010001111 000011100010 \
        010110010011 110011001100 110001001010 000001100011 100111110110 100011101101 \
        111000000011 000000010110 111101101101 100101100001 001101011101 101111100010; do
        echo "$r" | sed 's/1/255 /g; s/0/0 /g'
    done
} >abort.pgm
for alg in frontal delaunay; do
    measured 0 "mesh: the mask Gmsh aborted on ($alg)" mesh abort.pgm --simplify 2 --min-area 0.5 \
        --algorithm $alg -o m.msh
    [ -s m.msh ] || fail "mesh abort.pgm ($alg): no m.msh"
    rm -f m.msh
done
GLPGP_TEST_GMSH_FAULT=abort bad 1 'abort\.pgm: Gmsh crashed \(signal 6' "mesh: Gmsh child aborts" \
    mesh abort.pgm -o o.msh
GLPGP_TEST_GMSH_FAULT=segv bad 1 'abort\.pgm: Gmsh crashed \(signal 11' "solve MASK: Gmsh child crashes" \
    solve abort.pgm -o o.vtk --stats o.json
bad 1 'abort\.pgm: mesh size 1e-06 would make about .* triangles.*--max-elements' \
    "mesh: --mesh-size 1e-6 (far below a pixel)" mesh abort.pgm --mesh-size 1e-6 -o o.msh
GLPGP_TEST_GMSH_FAULT=hang bad 1 'abort\.pgm: Gmsh did not finish .* time limit of 0.5 s' \
    "mesh: Gmsh child hangs, --mesh-timeout 0.5" mesh abort.pgm --mesh-timeout 0.5 -o o.msh
bad 2 'image-size 20000.*--max-pixels' "render: --image-size beyond --max-pixels" \
    render r.vtk -o o.png --image-size 20000
if command -v python3 >/dev/null 2>&1; then
    python3 - <<'PY'
import struct, zlib
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
def png(w, h, idat): return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                             + chunk(b"IDAT", idat) + chunk(b"IEND", b""))
rows = b"".join(b"\0" + bytes(255 if 2 < i < 13 and 2 < j < 13 else 0 for i in range(16)) for j in range(16))
good = png(16, 16, zlib.compress(rows))
open("good.png", "wb").write(good)
open("trunc.png", "wb").write(good[:60])
bad = bytearray(good); bad[40] ^= 0xff; open("crc.png", "wb").write(bytes(bad))
open("short.png", "wb").write(png(64, 64, zlib.compress(b"\0" * 65 * 2)))
c = zlib.compressobj(9); row = b"\0" * 20001
open("huge.png", "wb").write(png(20000, 20000, b"".join(c.compress(row) for _ in range(20000)) + c.flush()))
PY
    echo "  (huge.png: $(wc -c <huge.png) bytes, 20000 x 20000)"
    bad 1 "huge\.png' has 20000 x 20000 = 400000000 pixels.*--max-pixels" "mesh: 20000 x 20000 PNG" \
        mesh huge.png -o o.msh
    bad 1 "huge\.png' has 20000 x 20000" "solve: 20000 x 20000 PNG" solve huge.png -o o.vtk
    for p in trunc crc short; do
        bad 1 "$p\.png" "mesh: $p.png (no libpng line)" mesh $p.png -o o.msh
        ! grep -q libpng err.txt || fail "$p.png: libpng wrote on stderr: $(cat err.txt)"
    done
    measured 0 "mesh: good.png" mesh good.png --min-area 1 -o m.msh
    rm -f m.msh
else
    echo "  (PNG cases skipped: no python3)"
fi

# SIGTERM while Gmsh meshes: exit 143, no output, and the Gmsh process is gone
awk 'BEGIN { print "P2"; print 64, 64; print 255; for (j = 0; j < 64; j++) { l = "";
     for (i = 0; i < 64; i++) l = l (((i - 32) ^ 2 + (j - 32) ^ 2 < 900) ? 255 : 0) " "; print l } }' >sig.pgm
runs=$((runs + 1))
"$GLPGP" mesh sig.pgm --mesh-size 0.05 -o sig.msh >out.txt 2>err.txt </dev/null &
pid=$!
sleep 1.5
kids=$(pgrep -P "$pid" | tr '\n' ' ')
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 143 ] || fail "SIGTERM during Gmsh: exit $rc, expected 143"
[ ! -e sig.msh ] || fail "SIGTERM during Gmsh: sig.msh written"
no_tmp "SIGTERM during Gmsh"
[ -n "$kids" ] || echo "  (SIGTERM: Gmsh had already finished or not started)"
sleep 0.5
for k in $kids; do # gone, or a zombie waiting for a reaper that does not reap (containers)
    state=$(awk '{ print $3 }' "/proc/$k/stat" 2>/dev/null)
    [ -z "$state" ] || [ "$state" = Z ] || fail "SIGTERM during Gmsh: the Gmsh process $k is still running ($state)"
done
finish
