#!/usr/bin/env bash
# bench/oscillators.sh: u and v one after the other against at the same time
# (`glpgp solve --oscillators sequential|concurrent`), whole solves, wall and
# CPU time and peak memory from /usr/bin/time, the same result checked (the
# two .vtu files byte for byte). Cases: a 107k-vertex CAD part (the motor
# lamination of bench/hard_domains.c at 40 edges per H, meshed by Gmsh's
# Delaunay), the 64k vortex disk at 10 mean edges per period, squares of 250k
# and 1M vertices; OpenCL (the default device) with the multigrid and with
# Jacobi-CG, and the reference backend up to 250k vertices.
# Writes a Markdown table on stdout (bench/results/oscillators.md holds one).
#
# Usage: bash bench/oscillators.sh [BUILD_DIR] [--quick]
#   --quick: the disk only, on both backends (seconds; a smoke run)
set -u
B=build
QUICK=0
for a in "$@"; do
    case "$a" in
    --quick) QUICK=1 ;;
    *) B=$a ;;
    esac
done
G="$B/glpgp"
D="$B/bench/glpgp-domains"
[ -x "$G" ] || { echo "oscillators: $G not found (build first)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "oscillators: /usr/bin/time not found (Debian: time)" >&2; exit 1; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
FAILED=0

cases=()
if [ "$QUICK" = 1 ]; then
    cases+=("disk4k|shape:disk:4000 --size 0.21|opencl reference")
else
    if [ -x "$D" ] && "$G" mesh --help >/dev/null 2>&1; then
        "$D" 1 40 "$T" motor >/dev/null &&
            "$G" mesh "$T/motor.poly" -o "$T/motor.msh" --algorithm delaunay --quiet >/dev/null 2>&1 &&
            cases+=("motor 107k (CAD)|$T/motor.msh|opencl opencl-jacobi reference")
    else
        echo "note: no glpgp-domains or no Gmsh: the CAD part is left out" >&2
    fi
    cases+=("disk 64k, 10 edges|shape:disk:64000 --size 0.07734642|opencl opencl-jacobi reference")
    cases+=("square 250k|shape:square:250000|opencl opencl-jacobi reference")
    cases+=("square 1M|shape:square:1000000|opencl")
fi

echo "| case | backend | sequential s (CPU s, MiB) | concurrent s (CPU s, MiB) | speed-up | same result |"
echo "|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
    IFS='|' read -r name input backends <<<"$c"
    for be in $backends; do
        args="--backend ${be%-jacobi}"
        [ "$be" = opencl-jacobi ] && args="$args --precond jacobi"
        row="| $name | $be |"
        wall=()
        for m in sequential concurrent; do
            # shellcheck disable=SC2086
            if ! /usr/bin/time -f "%e %U %S %M" -o "$T/time_$m" "$G" solve $input $args --oscillators "$m" \
                --out "$T/$m.vtu" --quiet >"$T/out_$m" 2>&1; then
                echo "oscillators: $name $be $m failed: $(head -c 300 "$T/out_$m")" >&2
                FAILED=1
                row="$row failed |"
                wall+=(0)
                continue
            fi
            read -r e u s kb <"$T/time_$m"
            row="$row $e ($(awk -v u="$u" -v s="$s" 'BEGIN{printf "%.1f", u + s}'), $((kb / 1024))) |"
            wall+=("$e")
        done
        sp=$(awk -v a="${wall[0]}" -v b="${wall[1]}" 'BEGIN{if (b > 0) printf "%.2fx", a / b; else print "-"}')
        same=no
        cmp -s "$T/sequential.vtu" "$T/concurrent.vtu" && same=yes
        [ "$same" = yes ] || FAILED=1
        echo "$row $sp | $same |"
        rm -f "$T"/*.vtu
    done
done
exit $FAILED
