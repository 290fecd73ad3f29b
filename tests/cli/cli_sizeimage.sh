#!/usr/bin/env bash
# cli_sizeimage.sh: a user size field painted as a grey-level image
# (`--size-field IMAGE`, issue 13 item 1):
#  - a square whose image is black on the left half and white on the right,
#    --size-min 0.3: a valid all-quad mesh whose quads on the left third are
#    at least 3x smaller in area than those on the right third (the field is
#    0.3 h there, h on the right: (1/0.3)^2 = 11 before the gradation;
#    measured 6.3);
#  - the same image with --size-image-box shifted so that the domain only
#    sees the image's white border column: left and right quads alike (the
#    box is applied);
#  - an all-white image changes nothing: the result file is the default
#    (auto) one byte for byte;
#  - errors: an unreadable image and a missing one are one error line
#    (exit 1), a malformed or empty --size-image-box a usage error (exit 2).
# Skips (77) when glpgp was built without OpenImageIO.
. "$(dirname "$0")/lib.sh" "$@"

# pgm NAME W H EXPR: grey 8-bit image, 255 where EXPR(x, y) holds (x, y: pixel column, row from the top)
pgm() {
    awk -v w="$2" -v h="$3" 'BEGIN { printf "P2\n%d %d\n255\n", w, h;
        for (y = 0; y < h; y++) { for (x = 0; x < w; x++) printf "%d ", ('"$4"') ? 255 : 0; printf "\n" } }' >"$1"
}
pgm half.pgm 64 64 'x >= 32'
pgm white.pgm 8 8 '1'
echo "not an image" >garbage.png

"$GLPGP" solve shape:square:2000 --size-field white.pgm --backend reference >out.txt 2>err.txt </dev/null
if grep -q "built without" err.txt; then
    echo "skipped: $(head -1 err.txt)"
    exit 77
fi

# quad areas: mean area of the faces whose centroid lies in the left / right third of the bounding box
areas() {
    python3 - "$1" <<'PY'
import sys
V, F = [], []
for l in open(sys.argv[1]):
    p = l.split()
    if p and p[0] == "v": V.append((float(p[1]), float(p[2])))
    elif p and p[0] == "f": F.append([int(t.split("/")[0]) - 1 for t in p[1:]])
x0, x1 = min(v[0] for v in V), max(v[0] for v in V)
L, R = [], []
for f in F:
    xs, ys = [V[i][0] for i in f], [V[i][1] for i in f]
    n = len(f)
    a = 0.5 * abs(sum(xs[k] * ys[(k + 1) % n] - xs[(k + 1) % n] * ys[k] for k in range(n)))
    c = (sum(xs) / n - x0) / (x1 - x0)
    if c < 1 / 3: L.append(a)
    elif c > 2 / 3: R.append(a)
print(sum(L) / len(L), sum(R) / len(R))
PY
}

run_ok "half image" solve shape:square:8000 --size-field half.pgm --size-min 0.3 --backend reference \
    --quads q.obj --stats s.json
expect_out "valid +yes" "half image: valid quad mesh"
expect_out "quads +[0-9]+ quads, 0 other faces" "half image: all quads"
read -r aL aR <<<"$(areas q.obj)"
python3 -c "import sys; sys.exit(0 if $aR > 3 * $aL else 1)" ||
    fail "half image: left quads (mean area $aL) not 3x smaller than right ones ($aR)"

# the box shifted far left: the domain [0, 1]^2 only sees the image's rightmost (white) column
run_ok "half image, shifted box" solve shape:square:8000 --size-field half.pgm --size-min 0.4 \
    --size-image-box -10,0,-9,1 --backend reference --quads q2.obj
read -r bL bR <<<"$(areas q2.obj)"
python3 -c "import sys; sys.exit(0 if abs($bR - $bL) < 0.3 * $bR else 1)" ||
    fail "shifted box: left / right quads differ (mean areas $bL, $bR): the box was not applied"

run_ok "all-white image" solve shape:square:4000 --size-field white.pgm --backend reference -o white.vtk
run_ok "default size field" solve shape:square:4000 --backend reference -o auto.vtk
cmp -s white.vtk auto.vtk || fail "an all-white size image changed the result"

run_fail "garbage image" 1 "garbage.png" solve shape:square:2000 --size-field garbage.png --backend reference
one_error_line "garbage image"
run_fail "missing image" 1 "nothere.png" solve shape:square:2000 --size-field nothere.png --backend reference
one_error_line "missing image"
run_fail "bad box" 2 "size-image-box" solve shape:square:2000 --size-field half.pgm --size-image-box 1,2,3
run_fail "empty box" 2 "empty box" solve shape:square:2000 --size-field half.pgm --size-image-box 0,0,0,1
finish
