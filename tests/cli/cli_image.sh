#!/usr/bin/env bash
# cli_image.sh: end-to-end runs of the picture and image-domain commands.
# Usage: bash cli_image.sh <path-to-glpgp> <data-dir>
# Masks are written here as plain PGM files (awk), which OpenImageIO reads.
# Checks: `glpgp mesh MASK -o D.msh` (disk, and a square with a hole:
# 2 boundary loops); `glpgp solve MASK --image out.png` end to end (PNG
# signature, no temporary file left); `glpgp render r.vtk -o r.png|.jpg`;
# `glpgp figure` (naive PGP vs GL); clear messages and exit codes for bad
# input: unreadable image, empty mask, all-inside mask (exit 1), missing -o,
# unknown --image-kind, unwritable image type (exit 2).
# Skips (77) when glpgp was built without OpenImageIO or Gmsh.
. "$(dirname "$0")/lib.sh" "$@"

# pgm NAME W H AWK-EXPR(i, j -> 0/1): plain PGM, 255 = inside
pgm() {
    awk -v W="$2" -v H="$3" "BEGIN { print \"P2\"; print W, H; print 255;
        for (j = 0; j < H; j++) { line = \"\";
            for (i = 0; i < W; i++) { x = i + 0.5; y = H - j - 0.5; v = ($4) ? 255 : 0;
                line = line v \" \" } print line } }" >"$1"
}

pgm disk.pgm 64 64 '(x - 32) ^ 2 + (y - 32) ^ 2 < 26 ^ 2'
pgm holed.pgm 64 48 'x > 4 && x < 60 && y > 4 && y < 44 && (x - 32) ^ 2 + (y - 24) ^ 2 > 10 ^ 2'
pgm empty.pgm 16 16 '0'
pgm full.pgm 16 16 '1'
echo "not an image" >garbage.png

"$GLPGP" mesh disk.pgm -o probe.msh >out.txt 2>err.txt
grep -q "built without" err.txt && skip "$(head -1 err.txt)"

# ---- mesh ---------------------------------------------------------------------
run 0 "mesh disk" mesh disk.pgm -o disk.msh --pixel-size 0.03125 --mesh-size 0.1
[ -s disk.msh ] || fail "disk.msh missing"
grep -q "1 outer boundary, 0 holes" out.txt || fail "mesh disk: summary: $(head -2 out.txt)"
run 0 "mesh holed" mesh holed.pgm -o holed.obj --mesh-size 2
grep -q "1 hole" out.txt || fail "mesh holed: expected 1 hole: $(head -1 out.txt)"
[ -s holed.obj ] || fail "holed.obj missing"
run 1 "mesh --invert of the empty mask" mesh empty.pgm --invert -o inv.msh
grep -q "every pixel" err.txt || fail "inverted empty mask: message: $(head -c 300 err.txt)"
run 1 "mesh --invert of the full mask" mesh full.pgm --invert -o x.msh
grep -q "empty mask" err.txt || fail "inverted full mask: message: $(head -c 300 err.txt)"
no_tmp "mesh"

# ---- solve MASK --image -------------------------------------------------------
run 0 "solve mask --image" solve disk.pgm --pixel-size 0.03125 --size 0.5 --backend reference \
    --image out.png --image-size 200 --out r.vtk --quiet
[ -s out.png ] || fail "out.png missing"
if [ -s out.png ]; then
    head -c 8 out.png | od -An -c | grep -q "P   N   G" || fail "out.png is not a PNG"
fi
[ -s r.vtk ] || fail "r.vtk missing"
no_tmp "solve --image"

# ---- render / figure ------------------------------------------------------------
if [ -s r.vtk ]; then
    run 0 "render png" render r.vtk -o r.png --image-size 160 --background transparent
    [ -s r.png ] || fail "r.png missing"
    for k in checker zabs field theta; do
        run 0 "render --image-kind $k" render r.vtk -o "r_$k.jpg" --image-size 96 --image-kind "$k" --quiet
        [ -s "r_$k.jpg" ] || fail "r_$k.jpg missing"
    done
fi
run 0 "figure" figure shape:annulus:800 --field radial --size 0.5 --backend reference -o fig.png \
    --image-size 160 --quiet
[ -s fig.png ] || fail "fig.png missing"
no_tmp "render/figure"

# ---- errors -----------------------------------------------------------------------
run 1 "garbage image" mesh garbage.png -o g.msh
grep -q "cannot read image" err.txt || fail "garbage: message: $(head -c 300 err.txt)"
run 1 "missing image" mesh nosuch.png -o g.msh
grep -q "No such file" err.txt || fail "missing: message: $(head -c 300 err.txt)"
run 1 "empty mask" solve empty.pgm --backend reference --quiet
grep -q "empty mask" err.txt || fail "empty: message: $(head -c 300 err.txt)"
run 1 "all-inside mask" mesh full.pgm -o f.msh
grep -q "every pixel" err.txt || fail "full: message: $(head -c 300 err.txt)"
[ ! -e f.msh ] || fail "all-inside mask: f.msh written"
run 2 "mesh without -o" mesh disk.pgm
run 2 "bad --image-kind" solve disk.pgm --image x.png --image-kind nope
run 2 "bad image type" solve disk.pgm --image x.unknownext
run 2 "render bad size" render r.vtk -o x.png --image-size 3
run 1 "render missing result" render nosuch.vtk -o x.png
run 1 "render into missing dir" render r.vtk -o nodir/x.png
no_tmp "errors"

finish
