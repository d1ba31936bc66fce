#!/bin/sh
# make fixtures-check: every fixture tests/fixtures/NAME.txt computed anew into a temporary folder by
# the command on its first line (BUILD for its build/, the folder for its tests/fixtures) and
# compared with the committed file: the same lines, the comments identical, each value identical
# or within the file's round-off tolerance below (absolute, or relative to max(1, |value|)).
# Prints a line per
# fixture and "fixtures-check: N identical, N within round-off, N failed"; exits non-zero unless
# none failed. Usage: fixtures_check.sh [BUILD]
#
# The tolerances (the same build on the same machine gives every digit: the reference LAPACK is
# deterministic, and the plain and the sanitizer builds wrote the same files; another compiler
# or LAPACK rounds otherwise):
#  - continuum_solvers.txt, 1e-10 relative: the dense block's mu, which the test compares with the Arnoldi
#    iteration's to 1e-8; the two algorithms on the same pencil agree to 1.2e-10, the scale of
#    these mu's round-off. The grids, counts and signatures are integers and must be identical.
#  - continuum_refined_edges.txt, 5e-10 absolute: roots of the collision discriminant D at degree 48, an
#    ill-conditioned quantity (a pair of colliding mu moves by the square root of a perturbation):
#    near mode 2's root D changes sign back and forth within 1.6e-10 of it, so another round-off
#    moves the root that regula falsi finds within that band. The test compares the edges with
#    them to their error estimates (2e-9 and more) plus 1e-10.
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
identical=0
close=0
failed=0

# tolerance NAME: the largest difference allowed and "relative" or "absolute"
tolerance() {
  case $1 in
    continuum_solvers.txt) echo 1e-10 relative ;;
    continuum_refined_edges.txt) echo 5e-10 absolute ;;
    *) echo 0 absolute ;;
  esac
}

for f in tests/fixtures/*.txt; do
  [ -f "$f" ] || continue
  name=${f##*/}
  cmd=$(sed -n '1s/^# //p' "$f")
  # only a test program of the build writing this very file into tests/fixtures
  case $cmd in
    "build/tests/test_"*" --write-fixtures tests/fixtures $name") ;;
    *)
      echo "$name: FAILED: line 1 is not '# build/tests/test_... --write-fixtures tests/fixtures $name'"
      failed=$((failed + 1))
      continue ;;
  esac
  prog=${cmd%% *}
  prog=$build/${prog#build/}
  if ! "$prog" --write-fixtures "$tmp" "$name" >"$tmp/$name.log" 2>&1 || [ ! -f "$tmp/$name" ]; then
    echo "$name: FAILED: $prog --write-fixtures did not write it:"
    sed 's/^/  /' "$tmp/$name.log"
    failed=$((failed + 1))
    continue
  fi
  if cmp -s "$f" "$tmp/$name"; then
    echo "$name: identical ($(wc -l <"$f") lines)"
    identical=$((identical + 1))
    continue
  fi
  set -- $(tolerance "$name")
  if awk -v tol="$1" -v kind="$2" -v name="$name" '
    NR == FNR { a[FNR] = $0; n = FNR; next }
    { b[FNR] = $0; m = FNR }
    END {
      if (n != m) { printf "%s: FAILED: %d lines committed, %d computed\n", name, n, m; exit 1 }
      bad = 0; differ = 0; worst = 0
      for (i = 1; i <= n; i++) {
        if (a[i] == b[i]) continue
        differ++
        if (a[i] ~ /^#/ || b[i] ~ /^#/) {
          printf "%s:%d: FAILED: \"%s\" committed, \"%s\" computed\n", name, i, a[i], b[i]
          bad = 1
          continue
        }
        x = a[i] + 0; y = b[i] + 0
        d = x - y; if (d < 0) d = -d
        s = x < 0 ? -x : x; if (s < 1 || kind == "absolute") s = 1
        if (d / s > worst) worst = d / s
        if (d / s > tol) {
          printf "%s:%d: FAILED: %s committed, %s computed (%.2g %s, tolerance %g)\n", \
            name, i, a[i], b[i], d / s, kind, tol
          bad = 1
        }
      }
      if (bad) exit 1
      printf "%s: %d values differ, by %.2g %s at most (round-off tolerance %g)\n", name, \
        differ, worst, kind, tol
    }' "$f" "$tmp/$name"; then
    close=$((close + 1))
  else
    mkdir -p "$build/fixtures" && cp "$tmp/$name" "$build/fixtures/$name" &&
      echo "$name: the computed file is kept as $build/fixtures/$name"
    failed=$((failed + 1))
  fi
done
echo "fixtures-check: $identical identical, $close within round-off, $failed failed"
[ "$failed" -eq 0 ] && [ $((identical + close)) -gt 0 ]
